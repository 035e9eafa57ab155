"""What the turtles' pens drew: lines for the view, pixels for the colour sensor (pure)."""

import math

from .kinematics import PIXELS_PER_METER, WORLD_SIZE

DEFAULT_PEN = (0xB3, 0xB8, 0xFF)
DEFAULT_PEN_WIDTH = 3
MAX_POINTS = 20000  # the oldest lines go first beyond this many points


def to_pixel(x, y):
    """Return the window pixel (column, row) of a point in meters (rows go down)."""
    return x * PIXELS_PER_METER, (WORLD_SIZE - y) * PIXELS_PER_METER


class Canvas:
    """Pen lines as polylines of window pixels, one per pen colour and width."""

    def __init__(self):
        self.clear()

    def clear(self):
        """Erase everything drawn."""
        self.lines = []  # [(colour, width, [(column, row), ...])]
        self._pixels = {}  # (column, row) -> colour of the last line drawn over it
        self._points = 0
        self._open = {}  # turtle name -> the line it is extending

    def draw(self, turtle, start, end, colour, width):
        """Draw a pen line of `turtle` from `start` to `end` (meters)."""
        a, b = to_pixel(*start), to_pixel(*end)
        line = self._open.get(turtle)
        if line is None or line[0] != colour or line[1] != width or line[2][-1] != a:
            line = (colour, width, [a])
            self.lines.append(line)
            self._open[turtle] = line
        line[2].append(b)
        self._points += 1
        self._paint(a, b, colour, width)
        while self._points > MAX_POINTS and len(self.lines) > 1:
            self._points -= len(self.lines.pop(0)[2])

    def lift(self, turtle):
        """End `turtle`'s current line (its pen went up, or it jumped)."""
        self._open.pop(turtle, None)

    def colour_at(self, x, y):
        """Return the pen colour under a point (meters), or None where nothing is drawn."""
        column, row = to_pixel(x, y)
        return self._pixels.get((round(column), round(row)))

    def _paint(self, a, b, colour, width):
        steps = max(1, math.ceil(math.dist(a, b)))
        half = width // 2
        for i in range(steps + 1):
            column = round(a[0] + (b[0] - a[0]) * i / steps)
            row = round(a[1] + (b[1] - a[1]) * i / steps)
            for dc in range(-half, width - half):
                for dr in range(-half, width - half):
                    self._pixels[(column + dc, row + dr)] = colour
