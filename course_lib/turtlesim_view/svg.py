"""Draw a turtlesim scene as SVG, 500 by 500 pixels as the real window (pure)."""

from __future__ import annotations

import html
import math

from .scene import PenLine, Scene, TurtlePose

__all__ = ["PIXELS_PER_METER", "WINDOW_PIXELS", "describe", "render_svg"]

WINDOW_PIXELS = 500
PIXELS_PER_METER = 45  # turtlesim's: x = column / 45, y = (499 - row) / 45 (rows go down)
# A turtle seen from above, heading along +x, about the size of the real one's 45-pixel image.
_TURTLE = (
    '<ellipse cx="-9" cy="-9" rx="4" ry="3" fill="#3d8c40"/>'
    '<ellipse cx="-9" cy="9" rx="4" ry="3" fill="#3d8c40"/>'
    '<ellipse cx="8" cy="-9" rx="4" ry="3" fill="#3d8c40"/>'
    '<ellipse cx="8" cy="9" rx="4" ry="3" fill="#3d8c40"/>'
    '<circle cx="15" cy="0" r="5" fill="#3d8c40"/>'
    '<ellipse cx="0" cy="0" rx="13" ry="11" fill="#8a5a2b" stroke="#5c3a1a" stroke-width="2"/>'
    '<path d="M -6 -6 L 6 -6 L 6 6 L -6 6 Z" fill="none" stroke="#5c3a1a" stroke-width="1.5"/>'
)


def _rgb(colour: tuple[int, int, int]) -> str:
    return f"rgb({colour[0]},{colour[1]},{colour[2]})"


def _line(line: PenLine) -> str:
    points = " ".join(f"{c:.1f},{r:.1f}" for c, r in line.points)
    return (
        f'<polyline points="{points}" fill="none" stroke="{_rgb(line.colour)}" '
        f'stroke-width="{line.width}" stroke-linecap="round" stroke-linejoin="round"/>'
    )


def _turtle(turtle: TurtlePose) -> str:
    degrees = -math.degrees(turtle.theta)  # rows go down: a counter-clockwise turn is negative
    return (
        f'<g class="turtle" data-name="{html.escape(turtle.name, quote=True)}" '
        f'transform="translate({turtle.column:.2f} {turtle.row:.2f}) rotate({degrees:.2f})">'
        f"{_TURTLE}</g>"
    )


def describe(scene: Scene) -> str:
    """Return the window in words: each turtle's pose as /turtleN/pose gives it, the lines."""
    turtles = "; ".join(
        f"{t.name} at x {t.column / PIXELS_PER_METER:.2f}, "
        f"y {(WINDOW_PIXELS - 1 - t.row) / PIXELS_PER_METER:.2f}, "
        f"theta {round(t.theta, 2) + 0.0:.2f} rad"  # + 0.0: never "-0.00"
        for t in scene.turtles
    )
    lines = len(scene.lines)
    drawn = f"{lines} pen line{'' if lines == 1 else 's'} drawn" if lines else "nothing drawn"
    return f"{turtles or 'No turtle'}; {drawn}."


def render_svg(scene: Scene) -> str:
    """Return the window as an SVG document: its text alternative (a title and the turtles'
    poses in words), the background, pen lines, then the turtles."""
    size = WINDOW_PIXELS
    parts = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{size}" height="{size}" '
        f'viewBox="0 0 {size} {size}" role="img" '
        'aria-labelledby="turtlesim-title turtlesim-desc">',
        '<title id="turtlesim-title">TurtleSim window</title>',
        f'<desc id="turtlesim-desc">{html.escape(describe(scene))}</desc>',
        f'<rect id="background" width="{size}" height="{size}" fill="{_rgb(scene.background)}"/>',
        *(_line(line) for line in scene.lines),
        *(_turtle(turtle) for turtle in scene.turtles),
        "</svg>",
    ]
    return "\n".join(parts)
