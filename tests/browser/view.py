"""The 3D view in the page: screenshots of it, and whether the robot moves in it."""

from __future__ import annotations

import time
from pathlib import Path

from pixels import changed_fraction

__all__ = ["MOVED", "VIEW", "change_within", "shot", "wait_still"]

VIEW = 'iframe[title="3D view of the simulated robot"]'
MOVED = 0.002  # share of the view's pixels that change when the robot drives for a second


def shot(page, folder: Path, name: str, view: str = VIEW) -> tuple[bytes, Path]:  # type: ignore[no-untyped-def]
    """Screenshot the (first visible) 3D view; return the PNG and where it was kept."""
    path = folder / f"{name}.png"
    png = page.locator(view).first.screenshot(path=str(path))
    return png, path


def change_within(
    page, folder: Path, first: bytes, *, seconds: int, view: str = VIEW
) -> tuple[float, Path]:  # type: ignore[no-untyped-def]
    """Screenshot the view once a second until it differs from `first`; return the change."""
    change, path = 0.0, folder / "view_moving_1.png"
    for _ in range(seconds):
        page.wait_for_timeout(1000)  # screenshots a second apart (what is measured)
        later, path = shot(page, folder, "view_moving_1", view)
        change = changed_fraction(first, later)
        if change > MOVED:
            break
    return change, path


def wait_still(page, folder: Path, timeout: float = 10.0) -> float:  # type: ignore[no-untyped-def]
    """Wait until two views a second apart match; return the last change measured."""
    deadline = time.monotonic() + timeout
    before, _ = shot(page, folder, "stopping_0")
    change = 1.0
    while change > MOVED / 4 and time.monotonic() < deadline:
        page.wait_for_timeout(1000)  # the interval measured, not a wait for a condition
        after, _ = shot(page, folder, "stopping_1")
        change, before = changed_fraction(before, after), after
    return change
