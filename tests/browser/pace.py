"""A person's pace: how long a learner reads before the next cell, and the mistakes they make.

Reading times are drawn from a seeded generator (log-normal: most pauses short, a few long),
so a walk at a person's pace replays from its seed like any other walk. `WALK_PACE` picks the
pace: `ci` (seconds: `make test`), `person` (up to minutes: `make soak`), `none` (machine speed).
"""

from __future__ import annotations

import math
import os
import random
from dataclasses import dataclass

__all__ = ["CI_PACE", "MISTAKES", "PERSON_PACE", "Mistake", "Pace", "pace_from_env"]


@dataclass(frozen=True)
class Pace:
    """Reading times between cells: a median, a cap, and the cells after which one looks long.

    `linger_after`: sources of cells after which the learner always reads at least `linger_s`
    (lesson 7 says "look at the 3D view and the plot" right after setting the velocity).
    """

    name: str
    median_s: float
    cap_s: float
    linger_after: tuple[str, ...] = ()
    linger_s: float = 0.0

    def pause_s(self, rng: random.Random, source: str = "") -> float:
        """Return how long the learner reads after the cell `source` (0 at machine speed)."""
        if self.median_s <= 0:
            return 0.0
        drawn = min(self.cap_s, rng.lognormvariate(math.log(self.median_s), 0.9))
        if source.strip() in self.linger_after:
            drawn = max(drawn, self.linger_s)
        return round(drawn, 1)


# The cells after which the robot drives on while the learner looks at it: at 0.2 m/s it meets
# the red box 2.25 m ahead of its start after about 11 s.
_DRIVING_CELLS = (
    "%ros2 param set /param_vel_node velocity 0.2",
    "%ros2 param set /param_vel_node velocity 0.15",
)
CI_PACE = Pace("ci", median_s=1.5, cap_s=8.0, linger_after=_DRIVING_CELLS, linger_s=14.0)
PERSON_PACE = Pace("person", median_s=8.0, cap_s=180.0, linger_after=_DRIVING_CELLS, linger_s=30.0)
MACHINE_PACE = Pace("none", median_s=0.0, cap_s=0.0)
_PACES = {p.name: p for p in (CI_PACE, PERSON_PACE, MACHINE_PACE)}


def pace_from_env(default: Pace) -> Pace:
    """Return the pace `WALK_PACE` names (ci, person, none), else `default`."""
    name = os.environ.get("WALK_PACE", "")
    if name and name not in _PACES:
        raise ValueError(f"WALK_PACE={name!r}: use one of {', '.join(_PACES)}")
    return _PACES.get(name, default)


@dataclass(frozen=True)
class Mistake:
    """A mistaken cell a learner adds to lesson `lesson`, and what its hint must hold.

    Each leaves the lab as it was (refused, or a read): the walk goes on from the right answers.
    A mistake made on /param_vel_node while another step had stopped it (a kernel restarted, a
    lesson's `lesson.stop`, another lesson's driver) gets the hint of that instead.
    """

    lesson: int
    code: str
    shows: str  # a text its hint must hold while the node runs

    def expected(self) -> tuple[str, ...]:
        """Return the texts any one of which its hint must hold, whatever the lab's state."""
        return (self.shows, *(_NODE_GONE if "/param_vel" in self.code else ()))


# what the hint says when /param_vel_node is not running (the lab's state, not the mistake)
_NODE_GONE = ("/param_vel_node is not running", "no node '/param_vel", "there is no '/param_vel")

MISTAKES = (
    Mistake(7, "%ros2 param set /param_vel_node velocity 1", "double"),
    Mistake(7, "%ros2 param set /param_vel_node velocty 0.2", "'velocity'"),
    Mistake(7, "%ros2 param set /param_vel_node velocity 0.15 m/s", "0.15"),
    Mistake(7, "%ros2 param get /param_vel velocity", "'/param_vel_node'"),
    Mistake(6, "%ros2 param describe /param_vel_node speed", "param list /param_vel_node"),
    Mistake(5, "%ros2 run parameter_tests param_velocity", "param_vel"),
)
