"""How the browser tests wait for a page's state: a look every 100 ms, not every frame.

Playwright's `wait_for_function` looks at every animation frame unless told otherwise, which
keeps chromium drawing frames for as long as the wait lasts. Measured here on a lab page with
lesson 7 open, 15 s of waiting cost chromium 2.0 CPU-s (renderer 1.6, GPU process 0.4) that
way, against 0.2 CPU-s looking every 100 ms; lessons 1 to 11 in one lab (the full walk) used
244 CPU-s in all, 215 with this. The states the tests wait for last (a cell ran, a kernel is
idle, a terminal printed a line), so seeing them up to 100 ms late changes nothing. A wait for
one moment of an animation (the replay tests) keeps looking at every frame.
"""

from __future__ import annotations

__all__ = ["POLL_MS"]

POLL_MS = 100
