"""Judging lesson 11's travel exercise from measured motion; verdicts and hints (pure).

A verdict says what the robot did (on /odom since the exercise was armed), what
descriptor_vel_node held during the trip, and which of the learner's `param set` requests the
node refused and why, with the values the learner typed (the lab's parameter journal).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

from ..config.trip import (
    MAX_TRAVEL_M,
    TIME_MAX_S,
    TIME_STEP_S,
    VELOCITY_MAX_MPS,
    VELOCITY_STEP_MPS,
    Trip,
)
from .skills.judge import Verdict
from .skills.requests import Request

__all__ = [
    "HINTS",
    "NODE",
    "Held",
    "Request",
    "TravelAttempt",
    "TravelVerdict",
    "Verdict",
    "double",
    "holds_text",
    "judge_travel",
    "refusal",
    "replay",
]

NODE = "/descriptor_vel_node"
_ANSWER = (
    "one answer: `%ros2 param set /descriptor_vel_node travel_time {travel_time:.1f}`, then "
    "`%ros2 param set /descriptor_vel_node velocity {velocity:g}`."
)
_STEPS = (
    "velocity and travel_time are doubles (write 5.0, not 5): velocity up to 0.26 m/s in steps "
    "of 0.01, travel_time in steps of 0.1 s; set travel_time first, then velocity (setting "
    "velocity starts the trip)."
)
# what went wrong -> hints, from general to specific (attempt 1, 2, 3 and later)
HINTS: dict[str, tuple[str, str, str]] = {
    "distance": (
        "distance = velocity × travel_time. Which pair of values gives {target:.2f} m?",
        _STEPS,
        _ANSWER,
    ),
    "refused": (
        "only 'Set parameter successful' changes the node: read the answer under each "
        "`param set`; `%ros2 param get /descriptor_vel_node travel_time` shows what it holds.",
        _STEPS,
        _ANSWER,
    ),
    "no_limit": (
        "set travel_time before velocity: the node ends a trip after travel_time simulated "
        "seconds, and travel_time 0.0 means never.",
        _STEPS,
        _ANSWER,
    ),
}
# name -> (largest value, step, unit), as the node's descriptors declare them
_RANGES = {
    "velocity": (VELOCITY_MAX_MPS, VELOCITY_STEP_MPS, "m/s"),
    "travel_time": (TIME_MAX_S, TIME_STEP_S, "s"),
}


def double(value: float) -> str:
    """Return a double as the learner writes it: 0.2, 5.0, 0.0, 0.26."""
    text = f"{value:.2f}".rstrip("0")
    return text + "0" if text.endswith(".") else text


@dataclass(frozen=True)
class Held:
    """The node's velocity and travel_time (None: not known)."""

    velocity: float | None = None
    travel_time: float | None = None


@dataclass(frozen=True)
class TravelAttempt:
    """What the robot did during one attempt, what the node held, what it refused."""

    moved: bool
    stopped: bool  # it came to rest by itself
    distance_m: float
    passed_m: float = 0.0  # > 0: it went past this distance still moving: the check stopped it
    waited_s: float = 0.0  # > 0: still moving when the check's bound ran out: it stopped it
    held: Held = field(default_factory=Held)  # during the trip
    refusals: tuple[str, ...] = ()  # in the learner's words (see `refusal`)


@dataclass(frozen=True)
class TravelVerdict(Verdict):
    """A verdict, then what the re-armed node holds for the next attempt."""

    then: str = ""

    def __repr__(self) -> str:
        return super().__repr__() + (f"{self.then}\n" if self.then else "")


def _why(request: Request, held: Held) -> str:
    name, value = request.name, request.value
    if name == "max_travel":
        return "max_travel is read-only"
    if name not in _RANGES:
        return f"{NODE} has no parameter {name} (it has velocity, travel_time, max_travel)"
    if request.type_name == "integer":
        return f"it is an integer; write {float(value):.1f}"
    if request.type_name != "double":
        return f"it is a {request.type_name}, and {name} is a double; write a number like 0.2"
    top, step, unit = _RANGES[name]
    if not -1e-9 <= value <= top + 1e-9:
        return f"{name} goes from 0.0 to {top:g} {unit}"
    if abs(value / step - round(value / step)) > 1e-6:
        return f"{name} goes in steps of {step:g} {unit}"
    velocity = value if name == "velocity" else held.velocity
    travel_time = value if name == "travel_time" else held.travel_time
    if velocity is not None and travel_time is not None:
        trip = velocity * travel_time
        if trip > MAX_TRAVEL_M + 1e-9:
            return (
                f"a trip of {velocity:g} m/s for {travel_time:g} s is {trip:.2f} m, longer "
                f"than max_travel ({MAX_TRAVEL_M:g} m)"
            )
    return "the answer under the command says why"


def refusal(request: Request, held: Held) -> str:
    """Return why the node refused `request` while holding `held`, in the learner's words."""
    return f"Your `{request.name} {request.text}` was refused: {_why(request, held)}."


def replay(requests: Sequence[Request], at_arm: Held) -> tuple[Held, tuple[str, ...]]:
    """Return what the node held after the learner's requests (velocity: the last trip's,
    the last velocity above 0.0) and each refusal, once, in the order they came."""
    velocity, travel_time = at_arm.velocity, at_arm.travel_time
    trip_velocity = None
    refusals: dict[str, None] = {}
    for request in requests:
        if request.refused:
            refusals[refusal(request, Held(velocity, travel_time))] = None
        elif request.name in _RANGES and request.type_name == "double":
            if request.name == "travel_time":
                travel_time = request.value
            else:
                velocity = request.value
                trip_velocity = velocity if velocity > 0.0 else trip_velocity
    return Held(trip_velocity or velocity, travel_time), tuple(refusals)


def holds_text(held: Held) -> str:
    """Return what the node holds, said for the trip that setting velocity starts."""
    if held.velocity is None or held.travel_time is None:
        return f"{NODE} does not answer"
    if held.travel_time > 0.0:
        trip = f"setting velocity starts a trip of {double(held.travel_time)} s"
    else:
        trip = "no limit: a trip started now never ends; set travel_time first"
    return (
        f"{NODE} holds velocity {double(held.velocity)} and travel_time "
        f"{double(held.travel_time)} ({trip})"
    )


def _outcome(attempt: TravelAttempt, target_m: float, tolerance_m: float) -> str:
    cm = f"{tolerance_m * 100:g} cm"
    if not attempt.moved:
        return "the robot did not move."
    if attempt.passed_m:
        return (
            f"not yet. The robot passed {attempt.passed_m:.2f} m (the target {target_m:.2f} m "
            f"+ {cm}) still moving, so the check stopped it, at {attempt.distance_m:.2f} m."
        )
    if not attempt.stopped:
        bound = f" when the check's {attempt.waited_s:g} s ran out" if attempt.waited_s else ""
        return (
            f"not yet. The robot was still moving at {attempt.distance_m:.2f} m{bound}, so the "
            "check stopped it."
        )
    error = attempt.distance_m - target_m
    word = "short of" if error < 0 else "past"
    return (
        f"not yet. The robot travelled {attempt.distance_m:.2f} m and stopped, "
        f"{abs(error):.2f} m {word} the target ({target_m:.2f} m ± {cm})."
    )


def _endless(attempt: TravelAttempt) -> bool:
    return attempt.moved and not attempt.stopped and attempt.held.travel_time == 0.0


def _held_text(attempt: TravelAttempt) -> str:
    velocity, travel_time = attempt.held.velocity, attempt.held.travel_time
    if velocity is None or travel_time is None:
        return ""
    text = f"{NODE} held velocity {double(velocity)} and travel_time {double(travel_time)}"
    if _endless(attempt):
        return text + ", and travel_time 0.0 means no limit: the trip never ends by itself."
    if velocity > 0.0 and travel_time > 0.0:
        product = f"{double(velocity)} × {double(travel_time)} = {velocity * travel_time:.2f} m"
        return f"{text}: {product}."
    return text + "."


def _kind(attempt: TravelAttempt) -> str:
    if attempt.refusals:
        return "refused"
    return "no_limit" if _endless(attempt) else "distance"


def judge_travel(
    attempt: TravelAttempt,
    *,
    target_m: float,
    tolerance_m: float,
    number: int,
    show_hints: bool,
    answer: Trip,
) -> TravelVerdict:
    """Return the verdict on attempt `number` (1-based); hints only after a failure."""
    if attempt.stopped and abs(attempt.distance_m - target_m) <= tolerance_m:
        return TravelVerdict(
            True,
            f"Attempt {number}: passed! The robot travelled {attempt.distance_m:.2f} m "
            f"(target {target_m:.2f} m ± {tolerance_m * 100:g} cm) and stopped.",
        )
    parts = [f"Attempt {number}: {_outcome(attempt, target_m, tolerance_m)}"]
    parts += [_held_text(attempt), *attempt.refusals]
    if not attempt.moved and not attempt.refusals:
        parts.append("Set velocity above 0.0 (and travel_time, so that it stops by itself).")
    kind = _kind(attempt)
    words = {
        "target": target_m,
        "travel_time": answer.travel_time_s,
        "velocity": answer.velocity_mps,
    }
    ladder = HINTS[kind]
    hint = ladder[min(number, len(ladder)) - 1].format(**words) if show_hints else ""
    return TravelVerdict(False, " ".join(p for p in parts if p), hint, kind)
