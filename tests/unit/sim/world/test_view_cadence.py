"""The 3D view's cadence on the physics loop's wakes: evenly spaced frames (issue 23).

At 30 Hz on 50 Hz wakes the frames came 40, 40, 20 ms apart (a judder, and a sixth more
frames than 25 Hz); the wakes themselves jitter by a millisecond or two either way.
"""

from __future__ import annotations

import itertools
import random

from course_lib.sim.world.pacing import Cadence

WAKE_S = 0.02  # the physics loop at 50 Hz


def _frames(rate_hz: float, wakes: int, jitter_s: float, seed: int = 3) -> list[float]:
    rng = random.Random(seed)
    cadence = Cadence(1.0 / rate_hz, slack_s=WAKE_S / 4)
    times = [100.0 + i * WAKE_S + rng.uniform(-jitter_s, jitter_s) for i in range(wakes)]
    return [t for t in times if cadence.due(t)]


def test_25_hz_on_50_hz_wakes_takes_every_other_wake_despite_jitter() -> None:
    frames = _frames(25.0, 500, jitter_s=0.002)
    gaps = [round((b - a) / WAKE_S) for a, b in itertools.pairwise(frames)]
    assert set(gaps) == {2}, sorted(set(gaps))
    assert len(frames) == 250


def test_a_rate_above_the_wakes_takes_every_wake() -> None:
    assert len(_frames(120.0, 200, jitter_s=0.002)) == 200


def test_a_stall_starts_again_without_a_burst() -> None:
    cadence = Cadence(0.04, slack_s=0.005)
    assert cadence.due(10.0)
    assert not cadence.due(10.02)
    assert cadence.due(11.0)  # a second late: one frame, then the cadence from there
    assert not cadence.due(11.02)
    assert cadence.due(11.04)
