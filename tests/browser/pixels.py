"""Pure pixel statistics of screenshots: is a canvas blank, did its picture change."""

from __future__ import annotations

import io

import numpy as np
from PIL import Image

__all__ = ["changed_fraction", "is_blank", "load"]


def load(png: bytes) -> np.ndarray:
    """Return an RGB array of a PNG screenshot."""
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=np.int16)


def is_blank(png: bytes, *, min_std: float = 4.0, min_colors: int = 16) -> bool:
    """Return True if the picture is one flat colour (nothing rendered)."""
    image = load(png)
    colors = len(np.unique(image.reshape(-1, 3)[::7], axis=0))
    return float(image.std()) < min_std or colors < min_colors


def changed_fraction(before: bytes, after: bytes, *, threshold: int = 24) -> float:
    """Return the share of pixels whose colour moved by more than `threshold` in any channel."""
    a, b = load(before), load(after)
    if a.shape != b.shape:
        return 1.0
    return float((np.abs(a - b).max(axis=2) > threshold).mean())
