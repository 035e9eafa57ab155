"""Packages without their heavy `__init__`: each process loads only the parts it uses.

Some packages the course's processes import run far more at import than those processes use:
- `rosidl_generator_py`, imported by every generated message module for
  `import_type_support`, also imports its code generator (`generate_py`, through lark and
  empy): about 7.5 MiB and 40 modules in every process that uses a message; only a build
  ever calls it.
- `meshcat`, whose geometry and commands the simulation sends to its 3D view, also imports
  its notebook visualizer, hence IPython and Pillow: about 6 MiB and 115 modules in the
  simulation, which never uses them.
- `httpx`, which JupyterLab imports for its extension manager, also imports its command-line
  client (`httpx._main`: click, rich, pygments) when they are installed (import-linter brings
  them): 4.3 MiB and 94 modules in every Jupyter server.
- every generated interface package (`geometry_msgs.msg`, `std_srvs.srv`, ...) imports all
  its interfaces; a few have fixed-size arrays, which import numpy: `param_vel`, which
  publishes a Twist, loaded numpy (6.5 MiB) for geometry_msgs' covariance messages.
- a generated interface module with a fixed-size array imports numpy as it loads, though
  only building or checking such a message uses it. Every service type of Jazzy carries one
  (its introspection event's `ServiceEventInfo.client_gid`, `uint8[16]`), so every node
  loaded numpy for its parameter services: 10 MiB in `param_vel`, a kernel and a daemon.

A finder installed at interpreter start-up (a `.pth` file that `make setup` writes into the
environment, `install_pth`) loads these packages without running their `__init__`; each name
the `__init__` would have bound is imported on first use (PEP 562 `__getattr__`), so
`from rosidl_generator_py import generate_py` (a colcon build), `meshcat.Visualizer` (a
notebook) and `from geometry_msgs.msg import *` work as before. An interface package is
recognised by its `__init__`, which rosidl generates: only `from <package>._<module> import
<Name>  # noqa: F401` lines; any other `__init__` runs as written. Its modules whose
generated `import numpy` line would load numpy run without that line: their `numpy` is a
stand-in that imports numpy on first use (and then gives way to it).
"""

from __future__ import annotations

import importlib
import importlib.machinery
import os
import sys
from importlib._abc import Loader  # importlib.abc's Loader; importlib.abc imports typing
from types import ModuleType

TYPE_CHECKING = False  # typing is not imported: this module runs in every start of Python
if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    _Binding = tuple[str, str | None] | Callable[[], str]

__all__ = [
    "DEFERRED_MODULES",
    "ON_FIRST_USE",
    "PTH_NAME",
    "SLIM_PACKAGES",
    "install",
    "install_pth",
]

# After ros_wheels_bootstrapper.pth ("s" sorts after "r"), so the bootstrapper's re-execution
# happens before this module is imported, not after.
PTH_NAME = "slim_imports.pth"
_OLD_PTH_NAMES = ("rosidl_import.pth",)  # written by earlier versions of `make setup`


def _meshcat_viewer_assets_path() -> str:
    package = sys.modules["meshcat"]
    return os.path.join(os.path.dirname(package.__file__ or ""), "viewer")


# Package -> {name its __init__ binds: (submodule, attribute of it, or None for the submodule)}.
# A value that is a callable is bound as is (a function the __init__ itself defines).
SLIM_PACKAGES: dict[str, dict[str, _Binding]] = {
    "rosidl_generator_py": {
        "import_type_support": ("import_type_support_impl", "import_type_support"),
        "generate_py": ("generate_py_impl", "generate_py"),
    },
    "meshcat": {
        "commands": ("commands", None),
        "geometry": ("geometry", None),
        "visualizer": ("visualizer", None),
        "servers": ("servers", None),
        "transformations": ("transformations", None),
        "animation": ("animation", None),
        "Visualizer": ("visualizer", "Visualizer"),
        "viewer_assets_path": _meshcat_viewer_assets_path,
    },
}
# Module -> the one function its package takes from it: the module (and what it imports) is
# loaded when that function is first called.
DEFERRED_MODULES = {"httpx._main": "main"}
# Module -> modules it imports at its top but uses only in code the course never runs: each
# is imported on its first use. jupyter-server-proxy's handlers use aiohttp only to probe a
# process they started themselves (`server_processes`, which the course configures none of).
ON_FIRST_USE = {"jupyter_server_proxy.handlers": ("aiohttp",)}

# The names each package's own __init__ lists in __all__ (rosidl_generator_py lists
# generate_py only when its generator imports; it does here, with the build wheels).
_ALL = {"rosidl_generator_py": ["import_type_support", "generate_py"]}


_INTERFACE_KINDS = ("msg", "srv", "action")
_GENERATED_SUFFIX = "  # noqa: F401"
# How rosidl_generator_py imports numpy for a fixed-size array member (its `_idl.py.em`).
_GENERATED_NUMPY_IMPORT = "import numpy  # noqa: E402, I100\n"


def _interface_bindings(fullname: str, init_file: str) -> dict[str, _Binding] | None:
    """The names a generated interface package's `__init__` binds, or None if not generated."""
    try:
        with open(init_file, encoding="utf-8") as init:
            lines = [line.rstrip("\n") for line in init if line.strip()]
    except OSError:
        return None
    bindings: dict[str, _Binding] = {}
    for line in lines:  # from <fullname>._<module> import <Name>, then the suffix
        words = line.removesuffix(_GENERATED_SUFFIX).split(" ")
        if (
            not line.endswith(_GENERATED_SUFFIX)
            or len(words) != 4
            or words[::2] != ["from", "import"]
        ):
            return None
        package, _, module = words[1].rpartition(".")
        if package != fullname or not module.startswith("_") or not words[3].isidentifier():
            return None
        bindings[words[3]] = (module, words[3])
    return bindings or None


def _lazy_attribute(package: str, bindings: dict[str, _Binding]) -> Callable[[str], object]:
    def __getattr__(name: str) -> object:
        binding = bindings.get(name)
        if binding is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        if callable(binding):
            value: object = binding
        else:
            submodule, attribute = binding
            try:
                module = importlib.import_module(f"{package}.{submodule}")
            except ImportError as error:  # as the package's own __init__: no module, no name
                raise AttributeError(f"module {package!r} has no attribute {name!r}") from error
            value = module if attribute is None else getattr(module, attribute)
        setattr(sys.modules[package], name, value)  # found once; plain attribute from now on
        return value

    return __getattr__


class _PackageLoader(Loader):
    """Create the package from its real spec; bind its names lazily instead of its __init__."""

    def __init__(self, bindings: dict[str, _Binding], all_names: list[str] | None) -> None:
        self._bindings = bindings
        self._all = all_names

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType:
        module = ModuleType(spec.name)
        module.__spec__ = spec
        module.__path__ = list(spec.submodule_search_locations or [])
        module.__file__ = spec.origin
        return module

    def exec_module(self, module: ModuleType) -> None:
        if self._all is not None:
            vars(module)["__all__"] = list(self._all)
        module.__getattr__ = _lazy_attribute(module.__name__, self._bindings)  # type: ignore[method-assign]
        names = sorted(self._bindings)
        module.__dir__ = lambda: sorted({*vars(module), *names})  # type: ignore[method-assign]


class _DeferredLoader(Loader):
    """Stand in for a module with its one function; load the real module when it is called."""

    def __init__(self, real: importlib.machinery.ModuleSpec, function: str) -> None:
        self._real = real
        self._function = function

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> None:
        return None  # the default module

    def exec_module(self, module: ModuleType) -> None:
        real, function = self._real, self._function
        loaded: list[ModuleType] = []  # the real module, once a call has loaded it

        def deferred(*args: object, **kwargs: object) -> object:
            if not loaded:
                import importlib.util

                module = importlib.util.module_from_spec(real)
                sys.modules[real.name] = module
                assert real.loader is not None
                real.loader.exec_module(module)
                loaded.append(module)
            return getattr(loaded[0], function)(*args, **kwargs)

        deferred.__name__ = deferred.__qualname__ = function
        setattr(module, function, deferred)


class _ImportOnFirstUse:
    """Stand for a module a module imports at its top until the module first uses it."""

    def __init__(self, namespace: dict[str, object], name: str) -> None:
        self._namespace = namespace
        self._name = name

    def __getattr__(self, attribute: str) -> object:
        module = importlib.import_module(self._name)
        self._namespace[self._name] = module  # its later uses go to the module itself
        return getattr(module, attribute)


class _OnFirstUseLoader(Loader):
    """Run a module without its top-level `import <name>` statements for `names` (the same
    lines: a traceback still points at its own code); each name is a stand-in that imports
    the module on first use."""

    def __init__(self, path: str, names: tuple[str, ...]) -> None:
        self._path = path
        self._names = names

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> None:
        return None  # the default module

    def exec_module(self, module: ModuleType) -> None:
        import ast

        with open(self._path, encoding="utf-8") as file:
            tree = ast.parse(file.read(), self._path)
        namespace = vars(module)
        for index, statement in enumerate(tree.body):
            if not isinstance(statement, ast.Import):
                continue
            imported = [(alias.name, alias.asname) for alias in statement.names]
            if all(name in self._names and alias is None for name, alias in imported):
                tree.body[index] = ast.copy_location(ast.Pass(), statement)
                for name, _ in imported:
                    namespace[name] = _ImportOnFirstUse(namespace, name)
        exec(compile(tree, self._path, "exec"), namespace)


def _on_first_use(
    spec: importlib.machinery.ModuleSpec | None, names: tuple[str, ...]
) -> importlib.machinery.ModuleSpec | None:
    """Give `spec` the loader above if its module (source) would load one of `names` that is
    not loaded yet; return it (None: not found here, the next finder looks)."""
    waiting = tuple(name for name in names if name not in sys.modules)
    if spec is not None and waiting and (spec.origin or "").endswith(".py"):
        spec.loader = _OnFirstUseLoader(spec.origin or "", waiting)
    return spec


def _imports_numpy_for_an_array(path: str) -> bool:
    """Return True if a generated interface module imports numpy (its imports come before
    its first class: only those lines are read, not the whole module)."""
    try:
        with open(path, encoding="utf-8") as file:
            for line in file:
                if line.startswith("class "):
                    return False
                if line == _GENERATED_NUMPY_IMPORT:
                    return True
    except OSError:
        pass
    return False


def _interface_module_spec(
    fullname: str, path: Sequence[str] | None
) -> importlib.machinery.ModuleSpec | None:
    """Return a generated interface module's spec: numpy on first use if it imports numpy for
    a fixed-size array (None: not found here, the next finder looks)."""
    spec = importlib.machinery.PathFinder.find_spec(fullname, path)
    if (
        spec is None
        or "numpy" in sys.modules
        or not _imports_numpy_for_an_array(spec.origin or "")
    ):
        return spec
    return _on_first_use(spec, ("numpy",))


def _is_interface_module(fullname: str) -> bool:
    """Return True for `<package>.<msg|srv|action>._<module>` of a generated package."""
    parts = fullname.split(".")
    if len(parts) != 3 or parts[1] not in _INTERFACE_KINDS or not parts[2].startswith("_"):
        return False
    spec = getattr(sys.modules.get(f"{parts[0]}.{parts[1]}"), "__spec__", None)
    return spec is not None and isinstance(spec.loader, _PackageLoader)


class _Finder:
    """Find the packages as the path finder does, and give them the loader above."""

    def find_spec(
        self, fullname: str, path: Sequence[str] | None = None, target: ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        if fullname in DEFERRED_MODULES:
            real = importlib.machinery.PathFinder.find_spec(fullname, path)
            if real is None:
                return None
            return importlib.machinery.ModuleSpec(
                fullname, _DeferredLoader(real, DEFERRED_MODULES[fullname]), origin=real.origin
            )
        if _is_interface_module(fullname):
            return _interface_module_spec(fullname, path)
        if fullname in ON_FIRST_USE:
            spec = importlib.machinery.PathFinder.find_spec(fullname, path)
            return _on_first_use(spec, ON_FIRST_USE[fullname])
        interface = fullname.count(".") == 1 and fullname.rpartition(".")[2] in _INTERFACE_KINDS
        if not interface and fullname not in SLIM_PACKAGES:
            return None
        spec = importlib.machinery.PathFinder.find_spec(fullname, path)
        if spec is None or not spec.submodule_search_locations:
            return None  # not installed here: the import fails as it would without us
        if interface:
            bindings = _interface_bindings(fullname, spec.origin or "")
            if bindings is None:
                return None  # not generated by rosidl: its __init__ runs as written
            # A star import of the generated __init__ binds every interface, as here.
            spec.loader = _PackageLoader(bindings, sorted(bindings))
        else:
            spec.loader = _PackageLoader(SLIM_PACKAGES[fullname], _ALL.get(fullname))
        return spec


def install() -> None:
    """Put the finder first on `sys.meta_path` (once)."""
    if any(isinstance(f, _Finder) for f in sys.meta_path):
        return
    sys.meta_path.insert(0, _Finder())


def install_pth(site_packages: str | None = None) -> str:
    """Write the `.pth` file that installs the finder in every start of this environment."""
    import sysconfig
    from pathlib import Path

    from course_lib.core.files.atomic_files import atomic_write  # setup only: never at start-up

    folder = Path(site_packages or sysconfig.get_paths()["purelib"])
    for old in _OLD_PTH_NAMES:
        (folder / old).unlink(missing_ok=True)
    # One line starting with "import" (site runs those). It loads this file by its path, not
    # as course_lib's: importing course_lib at start-up would decide which course_lib every
    # process of the environment runs (a copy run from its own folder would run this one).
    code = (
        "try:\n"
        " import importlib.util as u\n"
        f" s = u.spec_from_file_location('_course_slim_imports', {str(Path(__file__))!r})\n"
        " m = u.module_from_spec(s)\n"
        " s.loader.exec_module(m)\n"
        " m.install()\n"
        "except OSError:\n"
        " pass\n"
    )
    return str(atomic_write(folder / PTH_NAME, f"import sys; exec({code!r})\n"))
