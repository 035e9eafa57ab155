"""The live speed plot's kept figure draws what speed_png draws, after any number of redraws
(samples and marks change between them): the learner sees the same picture, cheaper."""

from __future__ import annotations

import io
import math

import numpy as np
from PIL import Image

from course_lib.notebook.widgets.plotting import LiveSpeedFigure, speed_png

MARK, LINE = (0xC6, 0x28, 0x28), (0x15, 0x65, 0xC0)  # speed_png's colours


def _count(pixels: np.ndarray, color: tuple[int, int, int]) -> int:
    """Return how many pixels are (close to) `color`."""
    return int((np.abs(pixels - np.array(color)).max(axis=2) < 30).sum())


def _pixels(png: bytes) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=int)


def test_the_kept_figure_draws_what_speed_png_draws() -> None:
    times = [i * 0.02 for i in range(1500)]
    speeds = [0.2 * abs(math.sin(t / 5)) for t in times]
    marks = [(10.0, "velocity := 0.2"), (20.0, "velocity := -0.2")]
    figure = LiveSpeedFigure()
    figure.png(times[:100], speeds[:100], [])
    figure.png(times[:900], speeds[:900], marks[:1])
    for n, shown in ((1200, marks[:1]), (1500, marks)):
        live, still = (
            _pixels(figure.png(times[:n], speeds[:n], shown)),
            _pixels(speed_png(times[:n], speeds[:n], shown)),
        )
        assert live.shape == still.shape
        differing = np.abs(live - still).max(axis=2) > 40
        # laid out from another start, the axes may sit a pixel apart; the drawing is the same
        assert differing.mean() < 0.02, f"{differing.mean():.4f} of the pixels differ at {n}"
        for color in (MARK, LINE):
            drawn, expected = _count(live, color), _count(still, color)
            assert abs(drawn - expected) <= 0.1 * expected, (color, drawn, expected, n)
