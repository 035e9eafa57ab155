"""Turtlesim's window in the browser: the scene, its SVG, the page and the server showing it.

The course's turtlesim_node (rosject/turtlesim) has no Qt window; it serves this view instead
and prints its address as its first line.
"""

from .address import window_url
from .scene import PenLine, Scene, TurtlePose
from .server import WindowServer
from .svg import WINDOW_PIXELS, render_svg

__all__ = [
    "WINDOW_PIXELS",
    "PenLine",
    "Scene",
    "TurtlePose",
    "WindowServer",
    "render_svg",
    "window_url",
]
