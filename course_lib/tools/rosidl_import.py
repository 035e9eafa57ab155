"""Messages without their code generator: `rosidl_generator_py` loads only what a message needs.

Every generated message module imports `rosidl_generator_py` for `import_type_support`, and
that package's `__init__` also imports its code generator (`generate_py`, through lark and
empy): about 7.5 MiB and 40 modules in every process that uses a message, which only a build
ever calls. A finder installed at interpreter start-up (a `.pth` file that `make setup` writes
into the environment, `install_pth`) loads the package without running its `__init__`: it
binds `import_type_support` at once and `generate_py` on first use, so a colcon build that
generates messages works as before.
"""

from __future__ import annotations

import importlib
import importlib.machinery
import sys
from types import ModuleType

__all__ = ["PACKAGE", "PTH_NAME", "install", "install_pth"]

PACKAGE = "rosidl_generator_py"
# After ros_wheels_bootstrapper.pth ("ros_" sorts before "rosi"), so the bootstrapper's
# re-execution happens before this module is imported, not after.
PTH_NAME = "rosidl_import.pth"


def _generator_attribute(name: str) -> object:
    if name != "generate_py":
        raise AttributeError(f"module {PACKAGE!r} has no attribute {name!r}")
    try:
        module = importlib.import_module(f"{PACKAGE}.generate_py_impl")
    except ImportError as error:  # as the package's own __init__: no generator, no name
        raise AttributeError(f"module {PACKAGE!r} has no attribute {name!r}") from error
    return module.generate_py


class _PackageLoader:
    """Create the package from its real spec; run its type-support module, not its __init__."""

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType:
        module = ModuleType(spec.name)
        module.__spec__ = spec
        module.__path__ = list(spec.submodule_search_locations or [])
        module.__file__ = spec.origin
        return module

    def exec_module(self, module: ModuleType) -> None:
        impl = importlib.import_module(f"{PACKAGE}.import_type_support_impl")
        module.import_type_support = impl.import_type_support
        module.__all__ = ["import_type_support", "generate_py"]
        module.__getattr__ = _generator_attribute


class _Finder:
    """Find the package as the path finder does, and give it the loader above."""

    def find_spec(
        self, fullname: str, path: object = None, target: object = None
    ) -> importlib.machinery.ModuleSpec | None:
        if fullname != PACKAGE:
            return None
        spec = importlib.machinery.PathFinder.find_spec(fullname, path)
        if spec is None or not spec.submodule_search_locations:
            return None  # not installed here: the import fails as it would without us
        spec.loader = _PackageLoader()
        return spec


def install() -> None:
    """Put the finder first on `sys.meta_path` (once); a no-op if the package is imported."""
    if PACKAGE in sys.modules or any(isinstance(f, _Finder) for f in sys.meta_path):
        return
    sys.meta_path.insert(0, _Finder())


def install_pth(site_packages: str | None = None) -> str:
    """Write the `.pth` file that installs the finder in every start of this environment."""
    import sysconfig
    from pathlib import Path

    from course_lib.core.atomic_files import atomic_write  # setup only: never at start-up

    folder = Path(site_packages or sysconfig.get_paths()["purelib"])
    target = folder / PTH_NAME
    # One line starting with "import" (site runs those). It loads this file by its path, not
    # as course_lib's: importing course_lib at start-up would decide which course_lib every
    # process of the environment runs (a copy run from its own folder would run this one).
    code = (
        "try:\n"
        " import importlib.util as u\n"
        f" s = u.spec_from_file_location('_course_rosidl_import', {str(Path(__file__))!r})\n"
        " m = u.module_from_spec(s)\n"
        " s.loader.exec_module(m)\n"
        " m.install()\n"
        "except OSError:\n"
        " pass\n"
    )
    return str(atomic_write(target, f"import sys; exec({code!r})\n"))
