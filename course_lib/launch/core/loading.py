"""Read launch files: Python ones here; XML and YAML through the front end registered here.

The front end (`frontend.py`) builds actions, and actions include more launch files: so it
registers its loader here (`register_frontend`) instead of being imported by this module.
Python launch files import `launch`/`launch_ros`: they are loaded inside `shim.launch_modules()`,
which every entry point (`cli`, `describe`, `dry_run`) holds while it loads and runs.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from importlib.machinery import SourceFileLoader
from importlib.util import module_from_spec, spec_from_loader
from typing import Any

__all__ = [
    "LOADED_LAUNCH_FILES",
    "CourseUnavailableError",
    "InvalidFrontendLaunchFileError",
    "InvalidLaunchFileError",
    "InvalidPythonLaunchFileError",
    "is_frontend_filename",
    "load_any_launch_file",
    "load_frontend_launch_file",
    "load_python_launch_file",
    "register_frontend",
]

LOADED_LAUNCH_FILES: set[str] = set()  # paths evaluated so far, to name them in errors
XML_EXTENSIONS = ("launch.xml", "xml", "launch")
YAML_EXTENSIONS = ("launch.yaml", "launch.yml", "yaml", "yml", "launch")
_frontend: list[Callable[[str], Any]] = []


class CourseUnavailableError(ImportError):
    """A launch file uses part of launch/launch_ros that the course does not have."""


class InvalidPythonLaunchFileError(Exception):
    """The Python launch file has no `generate_launch_description()`."""


class InvalidLaunchFileError(Exception):
    """No loader could read the launch file; lists what each loader raised."""

    def __init__(self, extension: str = "", *, likely_errors: list[Exception] | None = None):
        self.likely_errors = likely_errors or []
        if extension == "" or not self.likely_errors:
            message = "The launch file may have a syntax error, or its format is unknown"
        else:
            several = "multiple exceptions" if len(self.likely_errors) > 1 else "exception"
            message = f"Caught {several} when trying to load file of format [{extension}]:"
            for error in self.likely_errors:
                message += f"\n - {type(error).__name__}: {error}"
            self.__cause__ = self.likely_errors[0]
        super().__init__(message)
        self._message = message

    def __str__(self) -> str:
        return self._message


class InvalidFrontendLaunchFileError(InvalidLaunchFileError):
    """No front end (XML, YAML) could read the file."""


def is_frontend_filename(filename: str) -> bool:
    """Return whether a front end (XML, YAML) claims this file name."""
    return any(filename.endswith("." + ext) for ext in (*XML_EXTENSIONS, *YAML_EXTENSIONS))


def register_frontend(loader: Callable[[str], Any]) -> None:
    """Set the function that parses XML and YAML launch files (called by `frontend`)."""
    _frontend[:] = [loader]


def load_python_launch_file(path: str) -> Any:
    """Execute a Python launch file as a module and call `generate_launch_description()`."""
    LOADED_LAUNCH_FILES.add(os.path.abspath(path))
    loader = SourceFileLoader("python_launch_file", path)
    spec = spec_from_loader(loader.name, loader)
    if spec is None:
        raise RuntimeError("Failed to load module spec!")
    module = module_from_spec(spec)
    loader.exec_module(module)
    if not hasattr(module, "generate_launch_description"):
        raise InvalidPythonLaunchFileError(
            f"launch file at '{path}' does not contain the required function "
            "'generate_launch_description()'"
        )
    return module.generate_launch_description()


def load_frontend_launch_file(path: str) -> Any:
    """Parse an XML or YAML launch file."""
    if not _frontend:
        raise RuntimeError("no front end registered (import course_lib.launch.frontend.reader)")
    LOADED_LAUNCH_FILES.add(os.path.abspath(path))
    return _frontend[0](path)


def load_any_launch_file(path: str) -> Any:
    """Load a launch file, trying the loader its extension suggests first."""
    loaders = [load_frontend_launch_file]
    extension = os.path.splitext(os.path.basename(path))[1][1:]
    if extension == "py":
        loaders.insert(0, load_python_launch_file)
    else:
        loaders.append(load_python_launch_file)
        extension = extension if is_frontend_filename(os.path.basename(path)) else ""
    errors: list[Exception] = []
    for loader in loaders:
        try:
            return loader(path)
        except CourseUnavailableError:
            raise  # one clear line, not a list of what each loader thought
        except Exception as exc:
            errors.append(exc)
    raise InvalidLaunchFileError(extension, likely_errors=errors)
