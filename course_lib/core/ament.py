"""Find ROS packages and their executables through the ament index, as `ros2 run` does."""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping
from pathlib import Path

from . import ament_index
from .errors import ExecutableNotFoundError, PackageNotFoundError
from .paths import WORKSPACE_INSTALL_DIR, append_once, prepend

__all__ = [
    "find_executable",
    "list_packages",
    "package_executables",
    "package_of_executable",
    "package_prefix",
    "package_share_directory",
    "use_workspace_interfaces",
    "workspace_env",
]


def _prefixes(env: Mapping[str, str] | None = None) -> list[Path]:
    listed = ament_index.prefix_path(os.environ if env is None else env)
    return [WORKSPACE_INSTALL_DIR] if listed is None else listed  # unsourced: the course's


def list_packages(env: Mapping[str, str] | None = None) -> dict[str, Path]:
    """Return every indexed package name with its prefix (first prefix wins)."""
    return ament_index.resources("packages", _prefixes(env))


def package_prefix(package: str, env: Mapping[str, str] | None = None) -> Path:
    """Return the install prefix of `package`."""
    prefix = ament_index.resource_prefix("packages", package, _prefixes(env))
    if prefix is None:
        raise PackageNotFoundError(package)
    return prefix


def package_share_directory(package: str, env: Mapping[str, str] | None = None) -> Path:
    """Return `<prefix>/share/<package>`."""
    return package_prefix(package, env) / "share" / package


def package_executables(package: str, env: Mapping[str, str] | None = None) -> list[str]:
    """Return the names of the executables in `<prefix>/lib/<package>`, sorted."""
    lib = package_prefix(package, env) / "lib" / package
    if not lib.is_dir():
        return []
    return sorted(p.name for p in lib.iterdir() if p.is_file() and os.access(p, os.X_OK))


def package_of_executable(executable: str, env: Mapping[str, str] | None = None) -> str | None:
    """Return the one package whose `lib/<package>/` holds `executable` (None: none or several)."""
    found = [
        package
        for package, prefix in sorted(list_packages(env).items())
        if (prefix / "lib" / package / executable).is_file()
    ]
    return found[0] if len(found) == 1 else None


def find_executable(package: str, executable: str, env: Mapping[str, str] | None = None) -> Path:
    """Return the path of `executable` in `package`."""
    available = package_executables(package, env)
    if executable not in available:
        raise ExecutableNotFoundError(package, executable, available)
    return package_prefix(package, env) / "lib" / package / executable


def _dsv_actions(prefix: Path, dsv: Path, seen: set[Path]) -> list[tuple[str, str, str]]:
    """Return (action, variable, value) from a colcon .dsv hook, following `source;` lines."""
    if dsv in seen or not dsv.is_file():
        return []
    seen.add(dsv)
    actions = []
    for line in dsv.read_text().splitlines():
        action, _, rest = line.partition(";")
        if action == "source":
            target = (prefix / rest) if not Path(rest).is_absolute() else Path(rest)
            if target.suffix == ".dsv":
                actions += _dsv_actions(prefix, target.resolve(), seen)
        elif rest:
            variable, _, value = rest.partition(";")
            path = (
                prefix / value
                if value and not Path(value).is_absolute()
                else Path(value or prefix)
            )
            actions.append((action, variable, str(path)))
    return actions


def _stamp(path: Path) -> tuple[str, int, int, int] | None:
    """Return what says a file changed: its path, inode, mtime and size (None if absent)."""
    try:
        info = path.stat()
    except OSError:
        return None
    return str(path), info.st_ino, info.st_mtime_ns, info.st_size


# prefix -> (the stamps of its packages' hook files, the actions they hold)
_HOOKS: dict[Path, tuple[tuple[object, ...], list[tuple[str, str, str]]]] = {}


def _hook_actions(prefix: Path) -> list[tuple[str, str, str]]:
    """Return the actions of every package's hooks in `prefix`, in package order.

    They are read again only when a package's hook file changed (colcon rewrites it at each
    build of that package): each terminal command's environment starts from them in the
    daemon, so no command parses them again.
    """
    packages_dir = prefix / "share" / "colcon-core" / "packages"
    names = sorted(p.name for p in packages_dir.iterdir()) if packages_dir.is_dir() else []
    hooks = [prefix / "share" / name / "package.dsv" for name in names]
    stamps = tuple(_stamp(hook) or str(hook) for hook in hooks)
    cached = _HOOKS.get(prefix)
    if cached is not None and cached[0] == stamps:
        return cached[1]
    seen: set[Path] = set()
    actions = [action for hook in hooks for action in _dsv_actions(prefix, hook, seen)]
    _HOOKS[prefix] = (stamps, actions)
    return actions


def _overlay(env: dict[str, str], prefix: Path) -> None:
    """Apply the hooks of every package installed in `prefix`, as its setup.bash would."""
    for action, variable, value in _hook_actions(prefix):
        if action.startswith("prepend-non-duplicate"):
            if action.endswith("if-exists") and not os.path.exists(value):
                continue
            env[variable] = append_once(value, env.get(variable))
        elif action == "set" or (action == "set-if-unset" and variable not in env):
            env[variable] = value


def workspace_env(base: Mapping[str, str] | None = None) -> dict[str, str]:
    """Return `base` with the course workspace added as if sourced before what base sourced.

    Packages resolve through AMENT_PREFIX_PATH in the caller's order: a learner's own
    workspace sourced after the course's (so listed before it) wins, as in a sourced shell.
    """
    env = dict(os.environ if base is None else base)
    install = WORKSPACE_INSTALL_DIR
    env["AMENT_PREFIX_PATH"] = append_once(str(install), env.get("AMENT_PREFIX_PATH"))
    env["COLCON_PREFIX_PATH"] = append_once(str(install), env.get("COLCON_PREFIX_PATH"))
    _overlay(env, install)
    env["PATH"] = prepend(str(Path(sys.executable).parent), env.get("PATH"))
    return env


def use_workspace_interfaces() -> None:
    """Let this process use the interfaces built in the workspace (tf2_msgs), as if sourced.

    Appends the workspace's Python folders to sys.path and its library folders to
    LD_LIBRARY_PATH (for child processes). This process read LD_LIBRARY_PATH when it started,
    so the type support libraries that ROS loads by name are loaded here once by path.
    """
    overlay = workspace_env({})
    for entry in overlay.get("PYTHONPATH", "").split(os.pathsep):
        if entry and entry not in sys.path:
            sys.path.append(entry)
    libraries = [p for p in overlay.get("LD_LIBRARY_PATH", "").split(os.pathsep) if p]
    existing = os.environ.get("LD_LIBRARY_PATH", "").split(os.pathsep)
    missing = [p for p in libraries if p not in existing]
    if missing:
        os.environ["LD_LIBRARY_PATH"] = os.pathsep.join([*missing, *filter(None, existing)])
    for folder in libraries:
        for library in sorted(Path(folder).glob("lib*__rosidl_typesupport_*.so")):
            _preload(library)


def _preload(library: Path) -> None:
    import ctypes

    if library not in _preloaded:
        ctypes.CDLL(str(library), mode=ctypes.RTLD_GLOBAL)
        _preloaded.add(library)


_preloaded: set[Path] = set()
