"""The course's errors: what happened, why, and what to try next, in one place."""

from __future__ import annotations

__all__ = [
    "ConfigError",
    "CourseError",
    "DomainUnavailableError",
    "ExecutableNotFoundError",
    "PackageNotFoundError",
    "ProcessStartError",
    "RuntimeDirError",
    "SessionClosedError",
    "SessionThreadError",
]


class CourseError(Exception):
    """An expected problem, explained for a learner; never shown as a traceback."""

    def __init__(self, message: str, *, hint: str = "") -> None:
        super().__init__(message)
        self.message = message
        self.hint = hint

    def __str__(self) -> str:
        return f"{self.message}\nTry: {self.hint}" if self.hint else self.message


class PackageNotFoundError(CourseError):
    """A ROS package is not in the ament index of the course's workspace."""

    def __init__(self, package: str) -> None:
        super().__init__(
            f"Package '{package}' not found",
            hint="check the spelling, then `make setup` to rebuild the workspace in rosject/.",
        )
        self.package = package


class ExecutableNotFoundError(CourseError):
    """A package has no executable of that name."""

    def __init__(self, package: str, executable: str, available: list[str]) -> None:
        listing = ", ".join(available) or "none"
        super().__init__(
            "No executable found",
            hint=f"package '{package}' has these executables: {listing}.",
        )
        self.package = package
        self.executable = executable


class ProcessStartError(CourseError):
    """A child process could not be started."""


class SessionClosedError(CourseError):
    """The session was closed; start a new one."""

    def __init__(self) -> None:
        super().__init__(
            "This course session is closed.",
            hint="run the lesson's first cell again (it starts a fresh session).",
        )


class SessionThreadError(CourseError):
    """The session's ROS thread stopped on an error (logged with its traceback)."""

    def __init__(self, error: BaseException) -> None:
        super().__init__(
            f"the session's ROS thread stopped: {type(error).__name__}: {error}; "
            "run the first cell again"
        )
        self.error = error


class DomainUnavailableError(CourseError):
    """Every usable ROS domain id on this host is in use (course sessions or other programs)."""


class RuntimeDirError(CourseError):
    """The course's runtime folder (locks, markers, sockets) is not private to this user."""


class ConfigError(CourseError):
    """An instructor YAML file is invalid; names the file, line and key."""

    def __init__(self, path: str, line: int | None, key: str, problem: str, hint: str) -> None:
        where = f"{path}, line {line}" if line else path
        super().__init__(f"{where}: {key}: {problem}", hint=hint)
        self.path = path
        self.line = line
        self.key = key
