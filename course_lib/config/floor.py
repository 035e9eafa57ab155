"""The floor plane's geometry: what the robot meets driving straight on (pure: no MuJoCo).

The robot's footprint swept along its heading, against the obstacles of simulation.yaml and
the floor's edge. The instructor's files are checked with it (`together`: the lessons' drives
from the start pose), and the lessons measure with it wherever the robot stands now (a learner
who reads for a minute lets it drive on).
"""

from __future__ import annotations

import colorsys
import math
from dataclasses import dataclass

from .simulation import Obstacle, SimulationSettings

__all__ = ["FLOOR_EDGE", "FLOOR_HALF_M", "Ahead", "blocker", "free_ahead", "obstacle_words"]

FLOOR_HALF_M = 5.0  # scene.xml: the floor plane is 10 m × 10 m around the origin
FLOOR_EDGE = "the edge of the floor"
# The Waffle Pi's footprint around base_footprint (turtlebot3_waffle_pi.xml): the base plate
# reaches 0.20 m back, the camera 0.09 m forward, the wheels 0.16 m to each side.
REAR_M, FRONT_M, HALF_WIDTH_M = 0.20, 0.09, 0.16
CLEARANCE_M = 0.05  # room kept between the robot and anything it must not touch
_STEP_M = 0.01

Point = tuple[float, float]


@dataclass(frozen=True)
class Ahead:
    """How far the robot can drive on from a pose, and what stops it (None: free to `limit`)."""

    free_m: float
    blocker: str | None


def _corners(
    cx: float, cy: float, yaw: float, back: float, front: float, half: float
) -> list[Point]:
    c, s = math.cos(yaw), math.sin(yaw)
    local = [(-back, -half), (front, -half), (front, half), (-back, half)]
    return [(cx + x * c - y * s, cy + x * s + y * c) for x, y in local]


def _separated(a: list[Point], b: list[Point]) -> bool:
    """Return True when convex polygons a and b do not overlap (separating axis test)."""
    for poly in (a, b):
        for i, (x1, y1) in enumerate(poly):
            x2, y2 = poly[(i + 1) % len(poly)]
            axis = (y1 - y2, x2 - x1)
            pa = [axis[0] * x + axis[1] * y for x, y in a]
            pb = [axis[0] * x + axis[1] * y for x, y in b]
            if max(pa) < min(pb) or max(pb) < min(pa):
                return True
    return False


def _hits(swept: list[Point], obstacle: Obstacle, yaw: float, origin: Point) -> bool:
    x, y = obstacle.position_m
    if obstacle.shape == "box":
        length, width = obstacle.size_m[0], obstacle.size_m[1]
        box = _corners(x, y, math.radians(obstacle.yaw_deg), length / 2, length / 2, width / 2)
        return not _separated(swept, box)
    radius = obstacle.size_m[0] / 2
    c, s = math.cos(yaw), math.sin(yaw)
    dx, dy = x - origin[0], y - origin[1]
    along, across = dx * c + dy * s, -dx * s + dy * c  # the cylinder in the robot's frame
    xs = [px * c + py * s - (origin[0] * c + origin[1] * s) for px, py in swept]
    nearest_x = min(max(along, min(xs)), max(xs))
    nearest_y = min(max(across, -HALF_WIDTH_M - CLEARANCE_M), HALF_WIDTH_M + CLEARANCE_M)
    return math.hypot(along - nearest_x, across - nearest_y) < radius


def blocker(
    sim: SimulationSettings,
    x: float,
    y: float,
    yaw: float,
    distance: float,
    *,
    backwards: bool = False,
) -> str | None:
    """Return what the robot at (x, y) heading `yaw` (rad) meets within `distance`, or None.

    It is the obstacle's name, or FLOOR_EDGE; `backwards` sweeps the footprint behind.
    """
    ahead, behind = (0.0, distance) if backwards else (distance, 0.0)
    swept = _corners(
        x,
        y,
        yaw,
        REAR_M + CLEARANCE_M + behind,
        FRONT_M + CLEARANCE_M + ahead,
        HALF_WIDTH_M + CLEARANCE_M,
    )
    if any(abs(px) > FLOOR_HALF_M or abs(py) > FLOOR_HALF_M for px, py in swept):
        return FLOOR_EDGE
    for obstacle in sim.obstacles:
        if _hits(swept, obstacle, yaw, (x, y)):
            return obstacle.name
    return None


def free_ahead(
    sim: SimulationSettings,
    x: float,
    y: float,
    yaw: float,
    *,
    limit: float,
    backwards: bool = False,
) -> Ahead:
    """Return how far (cm steps, up to `limit`) the robot can drive on, and what it meets."""
    met = blocker(sim, x, y, yaw, 0.0, backwards=backwards)
    if met is not None:
        return Ahead(0.0, met)
    low, high = 0.0, limit  # the footprint only grows with the distance: bisect
    met = blocker(sim, x, y, yaw, high, backwards=backwards)
    if met is None:
        return Ahead(round(limit, 2), None)
    while high - low > _STEP_M:
        middle = (low + high) / 2
        if blocker(sim, x, y, yaw, middle, backwards=backwards) is None:
            low = middle
        else:
            high = middle
    first = blocker(sim, x, y, yaw, high, backwards=backwards)  # the nearest of what it meets
    return Ahead(round(math.floor(low / _STEP_M + 1e-9) * _STEP_M, 2), first or met)


_COLOUR_WORDS = (  # hue bands (degrees) and the word a person uses for them
    (20, "red"),
    (45, "orange"),
    (70, "yellow"),
    (170, "green"),
    (260, "blue"),
    (340, "purple"),
    (360, "red"),
)


def _colour_word(rgb: tuple[float, float, float]) -> str:
    hue, lightness, saturation = colorsys.rgb_to_hls(*rgb)
    if saturation < 0.25:
        return "white" if lightness > 0.85 else "black" if lightness < 0.15 else "grey"
    degrees = hue * 360
    return next(word for top, word in _COLOUR_WORDS if degrees < top)


def obstacle_words(sim: SimulationSettings, name: str) -> str:
    """Return how a person names what the robot met: "the red box", "the edge of the floor"."""
    found = next((o for o in sim.obstacles if o.name == name), None)
    if found is None:
        return name
    noun = found.name.removeprefix("obstacle_").replace("_", " ") or found.shape
    colour = _colour_word(found.color)
    return f"the {noun}" if colour in noun.split() else f"the {colour} {noun}"
