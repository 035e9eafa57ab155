"""The skill exercises' verdicts and hints, from what was measured (pure).

A failed attempt gets the hint of what went wrong; the same mistake made again gets a more
specific hint, up to the third, which names the exact edit but still leaves it to the learner.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

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

# kind -> hints, from general to specific (attempt 1, 2, 3 and later)
HINTS: dict[str, tuple[str, str, str]] = {
    "no_motion": (
        "is velocity set on the node that drives the robot? `%ros2 param get {node} velocity`",
        "did `param set` answer 'Set parameter successful'? `velocity` is a double: a whole "
        "number such as 1 is refused ('Wrong parameter type'); write it with a decimal point.",
        "velocity = distance ÷ time = {distance_m:g} ÷ {time_s:g}, written as a double, set on "
        "{node} before you run the check.",
    ),
    "wrong_node": (
        "which node drives the robot? `%ros2 topic info /cmd_vel --verbose` names the publisher.",
        "{elsewhere} holds velocity {elsewhere_value:g}, but the robot follows {node}.",
        "set the same value on {node}: `%ros2 param set {node} velocity <value>`.",
    ),
    "too_short": (
        "distance = velocity × time: the check measures {time_s:g} s of simulated time.",
        "it drove {measured_m:.2f} m in {time_s:g} s, so at {measured_mps:.2f} m/s; "
        "{distance_m:g} m in the same time needs a higher velocity.",
        "velocity = {distance_m:g} ÷ {time_s:g} (m/s), set as a double on {node}.",
    ),
    "too_far": (
        "distance = velocity × time: the check measures {time_s:g} s of simulated time.",
        "it drove {measured_m:.2f} m in {time_s:g} s, so at {measured_mps:.2f} m/s; "
        "{distance_m:g} m in the same time needs a lower velocity.",
        "velocity = {distance_m:g} ÷ {time_s:g} (m/s), set as a double on {node}.",
    ),
    "not_started": (
        "the check judges the node you start after arming it: start {node} again.",
        "stop the running node first, then start it with the file that holds the new value.",
        "{how}",
    ),
    "integer": (
        "the node stopped at start-up: read its last line (InvalidParameterTypeException).",
        "`{param}` is declared as a double; `{written}` is read as an integer, and ROS does not "
        "convert it.",
        "write the value with a decimal point, `{target:.2f}`, in {source}.",
    ),
    "missing_file": (
        "the node's last line says why it ended: rcl could not open the params file.",
        "a relative path after `--params-file` starts in the folder the node runs in (the "
        "notebook's): check the file's name and folder, for example with `%ls my_files`.",
        "{how}",
    ),
    "unreadable": (
        "the node's last line says why it ended: rcl could not parse the params file (it "
        "names the line).",
        "look at {source} with `lesson.show_file(...)`: a bracket or quote left open, a tab, "
        "or a line indented differently from its neighbours.",
        "the file holds `{node}:`, under it `  ros__parameters:`, under that "
        "`    {param}: {target:.2f}`.",
    ),
    "no_file": (
        "the value must be there from the node's first second: give it to the node at start-up.",
        "`ros2 run` takes a params file after `--ros-args`: `--params-file <file>`.",
        "{how}",
    ),
    "wrong_key": (
        "the node started with {param} {first:g}: ROS applied nothing from {source}, and "
        "says nothing about it.",
        "the file's top key `{key}` names no node that runs; ROS applies a section only to the "
        "node it names.",
        "make the top key `{node}:` (or `/**:` for every node).",
    ),
    "no_parameter": (
        "the node started with velocity {first:g}: the launch file gave it no velocity.",
        "a Node action takes its values as `parameters=[{{'name': value}}]`.",
        "add `parameters=[{{'velocity': {target:.2f}}}]` to the Node of {source}.",
    ),
    "after_window": (
        "{measured_text} only after the node's first seconds: the value came later.",
        "the node started with {param} {first:g}; a value set after the start is not the "
        "start-up value. Put it in {source} before the start.",
        "{how}",
    ),
    "wrong_value": (
        "{measured_text}; the task wants {param} {target:g}.",
        "look at the value {source} gives: `lesson.show_file(...)`.",
        "write `{param}: {target:g}` (a double) in {source}, then start the node again.",
    ),
}

_MESSAGES = {
    "no_motion": "the robot did not move.",
    "wrong_node": "the robot did not drive the distance.",
    "too_short": "the robot drove {measured_m:.2f} m in {time_s:g} s, short of {distance_m:g} m "
    "(± {tolerance_cm:g} cm).",
    "too_far": "the robot drove {measured_m:.2f} m in {time_s:g} s, past {distance_m:g} m "
    "(± {tolerance_cm:g} cm).",
    "not_started": "no {executable} was started by this lesson since the exercise was armed.",
    "integer": "{node} did not start: its {param} is an integer.",
    "missing_file": "{node} did not start: there is no file {source}.",
    "unreadable": "{node} did not start: ROS cannot read {source}.",
    "no_file": "{node} started without a params file.",
    "wrong_key": "{node} started with {param} {first:g}: the params file did not reach it.",
    "no_parameter": "{node} started with {param} {first:g}: the launch file sets none.",
    "after_window": "{node} started with {param} {first:g}, and got {target:g} only later.",
    "wrong_value": "{measured_text}, not {target:g} {unit} (± {tolerance:g}).",
}


@dataclass(frozen=True)
class Verdict:
    """The checker's answer to one attempt."""

    passed: bool
    message: str
    hint: str = ""
    kind: str = ""  # which mistake, for a failed skill exercise

    def __repr__(self) -> str:
        return self.message + (f"\nHint: {self.hint}" if self.hint else "") + "\n"


class _Words(dict):  # type: ignore[type-arg]
    def __missing__(self, key: str) -> str:
        return f"<{key}>"


def hint_for(kind: str, number: int, words: Mapping[str, Any]) -> str:
    """Return the hint for mistake `kind` at attempt `number` (1-based): later is more specific."""
    ladder = HINTS[kind]
    return ladder[min(number, len(ladder)) - 1].format_map(_Words(words))


def _failed(kind: str, number: int, words: Mapping[str, Any], show_hints: bool) -> Verdict:
    message = f"Attempt {number}: not yet. " + _MESSAGES[kind].format_map(_Words(words))
    return Verdict(False, message, hint_for(kind, number, words) if show_hints else "", kind)


@dataclass(frozen=True)
class DriveAttempt:
    """Lesson 7: what the robot did during the checker's window, and the node's value."""

    distance_m: float
    velocity: float | None  # the graded node's velocity now
    elsewhere: str = ""  # another node that holds the wanted velocity (the wrong node)
    elsewhere_value: float = 0.0


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
    problem: str = ""  # what reading that file found (see measure.FileValue)
    written: str = ""  # the value as the file writes it (for the integer hint)
    key: str = ""  # the params file's top key
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
    if attempt.problem in ("integer", "missing_file", "unreadable"):  # it ended at start-up
        return _failed(attempt.problem, number, words, show_hints)
    if task.needs_file and not attempt.source:
        return _failed("no_file", number, words, show_hints)
    if attempt.problem in ("wrong_key", "no_parameter") and not right_first:
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
