"""Judging lesson 11's travel exercise from measured motion; verdicts and hints (pure)."""

from __future__ import annotations

from dataclasses import dataclass

from ..config.trip import Trip
from .skills.judge import Verdict

__all__ = ["HINTS", "TravelAttempt", "Verdict", "judge_travel"]

HINTS = (
    "distance = velocity × travel_time. Which pair of values gives {target:.2f} m?",
    "velocity must be a multiple of 0.01 up to 0.26 m/s, travel_time a multiple of 0.1 s; "
    "set travel_time first, then velocity (setting velocity starts the trip).",
    "one answer: `%ros2 param set /descriptor_vel_node travel_time {travel_time:.1f}`, then "
    "`%ros2 param set /descriptor_vel_node velocity {velocity:g}`.",
)


@dataclass(frozen=True)
class TravelAttempt:
    """What the robot did during one attempt."""

    moved: bool
    stopped: bool
    distance_m: float


def judge_travel(
    attempt: TravelAttempt,
    *,
    target_m: float,
    tolerance_m: float,
    number: int,
    show_hints: bool,
    answer: Trip,
) -> Verdict:
    """Return the verdict on attempt `number` (1-based); hints only after a failure."""
    error = attempt.distance_m - target_m
    if not attempt.moved:
        message = (
            f"Attempt {number}: the robot did not move. Set velocity above 0.0 "
            "(and travel_time, so that it stops by itself)."
        )
    elif not attempt.stopped:
        message = (
            f"Attempt {number}: the robot was still moving after {attempt.distance_m:.2f} m. "
            "With travel_time 0.0 it never stops by itself."
        )
    elif abs(error) <= tolerance_m:
        return Verdict(
            True,
            f"Attempt {number}: passed! The robot travelled {attempt.distance_m:.2f} m "
            f"(target {target_m:.2f} m ± {tolerance_m * 100:g} cm) and stopped.",
        )
    else:
        word = "short of" if error < 0 else "past"
        message = (
            f"Attempt {number}: not yet. The robot travelled {attempt.distance_m:.2f} m and "
            f"stopped, {abs(error):.2f} m {word} the target ({target_m:.2f} m ± "
            f"{tolerance_m * 100:g} cm)."
        )
    words = {
        "target": target_m,
        "travel_time": answer.travel_time_s,
        "velocity": answer.velocity_mps,
    }
    hint = HINTS[min(number, len(HINTS)) - 1].format(**words) if show_hints else ""
    return Verdict(False, message, hint)
