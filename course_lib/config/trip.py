"""Lesson 11's exercise in numbers: the answer and the deliberately wrong attempt (pure).

`descriptor_vel_node` (rosject/parameter_descriptors) accepts a velocity in [0, 0.26] m/s in
steps of 0.01, a travel_time in [0, 30] s in steps of 0.1, and refuses a trip longer than its
read-only max_travel (1.5 m). The lesson's stored answer, its hint and the configuration check
all come from `answer_trip`, so the notebook's numbers always solve the configured exercise.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = [
    "MAX_TRAVEL_M",
    "TIME_MAX_S",
    "TIME_STEP_S",
    "VELOCITY_MAX_MPS",
    "VELOCITY_STEP_MPS",
    "Trip",
    "answer_trip",
    "wrong_trip",
]

VELOCITY_MAX_MPS = 0.26
VELOCITY_STEP_MPS = 0.01
TIME_MAX_S = 30.0
TIME_STEP_S = 0.1
MAX_TRAVEL_M = 1.5


@dataclass(frozen=True)
class Trip:
    """A travel_time and a velocity the node accepts."""

    travel_time_s: float
    velocity_mps: float

    @property
    def distance_m(self) -> float:
        """Return the commanded distance, velocity × travel_time."""
        return self.travel_time_s * self.velocity_mps


def _velocities(preferred: float) -> list[float]:
    steps = round(VELOCITY_MAX_MPS / VELOCITY_STEP_MPS)
    grid = [round(i * VELOCITY_STEP_MPS, 2) for i in range(1, steps + 1)]
    return sorted(grid, key=lambda v: (abs(v - preferred), -v))


def answer_trip(target_m: float, tolerance_m: float, preferred_mps: float) -> Trip | None:
    """Return a trip the node accepts that lands within half the tolerance of the target.

    The velocity closest to `preferred_mps` (the course's default velocity) comes first; half
    the tolerance leaves room for the robot's start and stop (about 1 cm). None: no trip does.
    """
    for velocity in _velocities(preferred_mps):
        travel_time = round(round(target_m / velocity / TIME_STEP_S) * TIME_STEP_S, 1)
        if not TIME_STEP_S <= travel_time <= TIME_MAX_S:
            continue
        trip = Trip(travel_time, velocity)
        if trip.distance_m > MAX_TRAVEL_M + 1e-9:
            continue
        if abs(trip.distance_m - target_m) <= tolerance_m / 2 + 1e-9:
            return trip
    return None


def wrong_trip(answer: Trip) -> Trip:
    """Return the lesson's deliberately wrong first attempt: half the speed, 80 % of the time."""
    velocity = max(VELOCITY_STEP_MPS, round(answer.velocity_mps / 2, 2))
    travel_time = max(TIME_STEP_S, round(answer.travel_time_s * 0.8, 1))
    return Trip(travel_time, velocity)
