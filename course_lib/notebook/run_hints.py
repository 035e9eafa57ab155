"""The pure hints of a failed `ros2 run`: a package or executable that does not exist, and a
params file that stopped the node at start-up (rcl could not read it, or a value's type)."""

from __future__ import annotations

import difflib
import os
import re
import shlex
from collections.abc import Callable, Iterable, Sequence

from .value_hints import closest, type_hint

__all__ = ["NO_EXECUTABLE", "NO_PACKAGE", "file_crash_hint", "run_hint", "run_words"]

NO_EXECUTABLE = "No executable found"
NO_PACKAGE = re.compile(r"Package '([^']*)' not found")
FILE_TYPE_CRASH = re.compile(  # rclpy's words when a params file's value has the wrong type
    r"InvalidParameterTypeException: Trying to set parameter '([^']+)' to '([^']*)' of type "
    r"'(\w+)', expecting type '(\w+)'"
)
FILE_UNREAD_CRASH = re.compile(  # rcl's words when it cannot open or parse a params file
    r"Couldn't parse params file: '--params-file (?P<file>[^']+)'\. Error: (?P<error>.+?)"
    r"(?:, at [^,]+:\d+)*$"
)


# --- pure: `ros2 run` ----------------------------------------------------------------------
def run_words(argv: Sequence[str]) -> tuple[str, str, list[str]] | None:
    """Return (package, executable, the arguments after them) of a `run` command line."""
    if not argv or argv[0] != "run":
        return None
    names: list[str] = []
    rest = list(argv[1:])
    while rest and len(names) < 2:
        token = rest.pop(0)
        if token == "--prefix":
            rest = rest[1:]
        elif not token.startswith("-"):
            names.append(token)
    return (names[0], names[1], rest) if len(names) == 2 else None


def _run_command(package: str, executable: str, rest: Sequence[str]) -> str:
    return f"`%ros2 {shlex.join(['run', package, executable, *rest])}`"


def _executable_step(
    package: str, executable: str, rest: Sequence[str], known: Sequence[str]
) -> str:
    """Say which of `package`'s executables the learner meant, with the corrected command."""
    if executable in known:
        return _run_command(package, executable, rest) + "."
    near = difflib.get_close_matches(executable, sorted(known), n=3, cutoff=0.6)
    if len(near) > 1:
        names = " or ".join(f"'{n}'" for n in near)
        return f"did you mean {names}? For example {_run_command(package, near[0], rest)}."
    if near:
        return f"did you mean '{near[0]}'? {_run_command(package, near[0], rest)}."
    listing = ", ".join(known) or "none"
    return f"its executables are: {listing} (`%ros2 pkg executables {package}`)."


def run_hint(
    stderr: str,
    words: tuple[str, str, list[str]],
    packages: Sequence[str],
    executables_of: Callable[[str], Sequence[str]],
) -> str | None:
    """Return the hint for a `ros2 run` of a package or an executable that does not exist:
    the closest names (`packages`: every package; `executables_of(package)`: its
    executables) and the corrected command; None for another failure."""
    package, executable, rest = words
    missing = NO_PACKAGE.fullmatch(stderr.strip())
    if missing and missing.group(1) == package:
        near = closest(package, packages)
        if near is None:
            return (
                f"there is no package '{package}' and none with a close name; "
                "`%ros2 pkg executables` lists every package's executables."
            )
        known = executables_of(near)
        either = "" if executable in known else f"It has no '{executable}' either: "
        step = _executable_step(near, executable, rest, known)
        return f"there is no package '{package}'; did you mean '{near}'? {either}{step}"
    if stderr.strip() == NO_EXECUTABLE:
        step = _executable_step(package, executable, rest, executables_of(package))
        return f"package '{package}' has no executable '{executable}'; {step}"
    return None


def file_crash_hint(
    log_lines: Iterable[str], files: Sequence[str], *, cwd: str = ""
) -> str | None:
    """Return the hint for a node that a params file stopped at start-up, or None: rcl could
    not open or parse the file (rclpy's RCLError), or a value has the wrong type (rclpy's
    InvalidParameterTypeException). `cwd` is where the node ran (a relative path starts there)."""
    if not files:
        return None
    for line in log_lines:
        found = FILE_TYPE_CRASH.search(line)
        if found:
            name, value, got, expected = found.groups()
            reason = f"Wrong parameter type, expected 'Type.{expected}' got 'Type.{got}'"
            hint = type_hint(reason, name, value)
            return f"in {', '.join(files)}: {hint}" if hint else None
        unread = FILE_UNREAD_CRASH.search(line)
        if unread:
            return _unread_file_hint(unread["file"], unread["error"], cwd)
    return None


def _unread_file_hint(file: str, error: str, cwd: str) -> str:
    """Return the hint for a params file that rcl could not open or parse."""
    if error.startswith("Error opening YAML file"):
        where = f" in {cwd}" if cwd and not os.path.isabs(file) else ""
        folder = os.path.dirname(file) or "."
        return (
            f"there is no file {file}{where} (a relative path starts in the folder the node "
            f"runs in): check its name and folder, for example with `%ls {folder}`."
        )
    line = re.search(r"line(?:_num)? (\d+)", error)
    where = f"rcl stopped reading it at line {line[1]}" if line else f"rcl says: {error}"
    return (
        f"{file} is not a params file ROS can read ({where}): look there for a bracket or "
        "quote left open, a tab, or a line indented differently from its neighbours."
    )
