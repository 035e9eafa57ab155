"""The skill exercises' verdicts and hints, from what was measured (pure).

A failed attempt gets the hint of what went wrong; the same mistake made again gets a more
specific hint, up to the third, which names the exact edit but still leaves it to the learner.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ...config.trip import VELOCITY_MAX_MPS
from .verdict_texts import HINTS, MESSAGES

__all__ = [
    "HINTS",
    "DriveAttempt",
    "StartupAttempt",
    "StartupTask",
    "Verdict",
    "hint_for",
    "judge_drive",
    "judge_startup",
]


@dataclass(frozen=True)
class Verdict:
    """The checker's answer to one attempt."""

    passed: bool
    message: str
    hint: str = ""
    kind: str = ""  # which mistake, for a failed skill exercise
    note: str = ""  # one line about the attempt itself (its count could not be saved)

    def __repr__(self) -> str:
        hint = f"\nHint: {self.hint}" if self.hint else ""
        return self.message + hint + "\n" + (f"{self.note}\n" if self.note else "")


class _Words(dict[str, Any]):
    def __missing__(self, key: str) -> str:
        return f"<{key}>"


def hint_for(kind: str, number: int, words: Mapping[str, Any]) -> str:
    """Return the hint for mistake `kind` at attempt `number` (1-based): later is more specific."""
    ladder = HINTS[kind]
    return ladder[min(number, len(ladder)) - 1].format_map(_Words(words))


def _failed(kind: str, number: int, words: Mapping[str, Any], show_hints: bool) -> Verdict:
    message = f"Attempt {number}: not yet. " + MESSAGES[kind].format_map(_Words(words))
    return Verdict(False, message, hint_for(kind, number, words) if show_hints else "", kind)


@dataclass(frozen=True)
class DriveAttempt:
    """Lesson 7: what the robot did during the checker's window, and the node's value."""

    distance_m: float
    velocity: float | None  # the graded node's velocity now
    elsewhere: str = ""  # another node that holds the wanted velocity (the wrong node)
    elsewhere_value: float = 0.0
    refused: str = ""  # the learner's last velocity that `param set` refused, as typed


def _refused_text(attempt: DriveAttempt, node: str) -> str:
    """Say why a velocity was refused: the learner's own value if known, never one above the
    top speed as the fix."""
    top = f"a speed in m/s with a decimal point, at most {VELOCITY_MAX_MPS:g}"
    if not attempt.refused:
        return (
            "`velocity` is a double: a whole number is read as an integer and refused "
            f"('Wrong parameter type'); write {top}."
        )
    kept = f"{attempt.velocity:g}" if attempt.velocity is not None else "its old value"
    read = "an integer" if attempt.refused.lstrip("+-").isdigit() else "text"
    return (
        f"`{attempt.refused}` is read as {read} and `velocity` is a double, so ROS refused "
        f"it ('Wrong parameter type') and {node} kept velocity {kept}; write {top}."
    )


def _over_top_speed(attempt: DriveAttempt) -> bool:
    """Return whether the node holds a velocity the robot cannot reach."""
    return attempt.velocity is not None and abs(attempt.velocity) > VELOCITY_MAX_MPS + 1e-9


def judge_drive(
    attempt: DriveAttempt,
    *,
    distance_m: float,
    time_s: float,
    tolerance_m: float,
    node: str,
    number: int,
    show_hints: bool,
) -> Verdict:
    """Return the verdict on lesson 7's attempt `number`."""
    words = {
        "node": node,
        "distance_m": distance_m,
        "time_s": time_s,
        "tolerance_cm": tolerance_m * 100,
        "measured_m": attempt.distance_m,
        "measured_mps": attempt.distance_m / time_s,
        "elsewhere": attempt.elsewhere,
        "elsewhere_value": attempt.elsewhere_value,
        "velocity": attempt.velocity,
        "top": f"{VELOCITY_MAX_MPS:g}",
        "refused_text": _refused_text(attempt, node),
    }
    error = attempt.distance_m - distance_m
    if abs(error) <= tolerance_m:
        return Verdict(
            True,
            f"Attempt {number}: passed! The robot drove {attempt.distance_m:.2f} m in "
            f"{time_s:g} s (target {distance_m:g} m ± {tolerance_m * 100:g} cm).",
        )
    if attempt.elsewhere:
        return _failed("wrong_node", number, words, show_hints)
    if _over_top_speed(attempt):
        return _failed("over_top_speed", number, words, show_hints)
    if attempt.distance_m < 0.01:
        return _failed("no_motion", number, words, show_hints)
    return _failed("too_short" if error < 0 else "too_far", number, words, show_hints)


@dataclass(frozen=True)
class StartupAttempt:
    """Lessons 9 to 11: how the node started, what its file said, what the robot did.

    `first` is the parameter's value when the node started (its first tick's log line, or its
    file); `start` the value measured on /odom in the node's first seconds (a speed, or a trip's
    length in time); `now` the node's value when checked.
    """

    started: bool  # a node was started by this lesson since the exercise was armed
    source: str = ""  # the file meant to give the value (params or launch file); "" for none
    problem: str = ""  # what reading that file found (see file_values.FileValue)
    written: str = ""  # the value as the file writes it (for the integer hint)
    key: str = ""  # the params file's top key, or the name its problem is about (FileValue)
    first: float = 0.0
    start: float = 0.0
    now: float = 0.0
    measured_text: str = ""  # what was measured, as a sentence ("the robot drove at ...")
    elsewhere: str = ""
    elsewhere_value: float = 0.0


@dataclass(frozen=True)
class StartupTask:
    """What a start-up exercise asks: `param` at `target` from the node's start."""

    node: str
    executable: str
    param: str
    unit: str
    target: float
    tolerance: float
    how: str  # the most specific hint for starting the node right (without the value)
    needs_file: bool  # the node itself must be given a params file (lessons 9 and 11)


# what stopped the node at start-up (rcl or rclpy refused its file), see file_values.FileValue
_ENDED = (
    "integer",
    "missing_file",
    "unreadable",
    "no_ros_parameters",
    "empty_section",
    "no_node_key",
)
# a file that reached the node without the value: a launch file's, or a params file's
_GAVE_NOTHING = ("wrong_key", "no_parameter", "undeclared", "nested", "file_sets_none")


def judge_startup(
    attempt: StartupAttempt, task: StartupTask, *, number: int, show_hints: bool
) -> Verdict:
    """Return the verdict on a start-up exercise's attempt `number`."""
    words = {
        "node": task.node,
        "executable": task.executable,
        "param": task.param,
        "unit": task.unit,
        "how": task.how,
        "target": task.target,
        "tolerance": task.tolerance,
        "source": attempt.source or "the file",
        "written": attempt.written,
        "key": attempt.key,
        "first": attempt.first,
        "measured_text": attempt.measured_text,
        "elsewhere": attempt.elsewhere,
        "elsewhere_value": attempt.elsewhere_value,
    }
    right_first = abs(attempt.first - task.target) < 1e-6
    if not attempt.started:
        return _failed("not_started", number, words, show_hints)
    if attempt.problem in _ENDED:  # it ended at start-up
        return _failed(attempt.problem, number, words, show_hints)
    if task.needs_file and not attempt.source:
        return _failed("no_file", number, words, show_hints)
    if attempt.problem in _GAVE_NOTHING and not right_first:
        return _failed(attempt.problem, number, words, show_hints)
    if attempt.elsewhere and abs(attempt.now - task.target) > task.tolerance:
        return _failed("wrong_node", number, words, show_hints)
    if right_first and abs(attempt.start - task.target) <= task.tolerance:
        return Verdict(
            True,
            f"Attempt {number}: passed! {task.node} started with {task.param} "
            f"{attempt.first:g}; {attempt.measured_text} (target {task.target:g} {task.unit} "
            f"± {task.tolerance:g}).",
        )
    if not right_first and abs(attempt.now - task.target) <= task.tolerance:
        return _failed("after_window", number, words, show_hints)
    return _failed("wrong_value", number, words, show_hints)
