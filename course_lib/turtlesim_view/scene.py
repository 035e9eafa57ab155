"""What turtlesim's window shows, as plain data (pure)."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["PenLine", "Scene", "TurtlePose"]

Colour = tuple[int, int, int]


@dataclass(frozen=True)
class TurtlePose:
    """A turtle in window pixels: column, row (rows go down) and heading (rad, CCW)."""

    name: str
    column: float
    row: float
    theta: float


@dataclass(frozen=True)
class PenLine:
    """A pen line through window pixels."""

    colour: Colour
    width: int
    points: tuple[tuple[float, float], ...]


@dataclass(frozen=True)
class Scene:
    """The background colour, the pen lines (oldest first) and the turtles."""

    background: Colour
    lines: tuple[PenLine, ...] = ()
    turtles: tuple[TurtlePose, ...] = ()
