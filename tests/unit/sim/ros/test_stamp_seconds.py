"""A resting world's samples carry the stamp its messages would (sim.ros.messages)."""

from __future__ import annotations

import pytest

from course_lib.sim.ros.messages import stamp_seconds, to_stamp

TIMESTEP_S = 0.002  # config/simulation.yaml's physics step


def _summed(steps: int) -> float:
    """Return the simulated time after `steps` steps, summed one by one as the world does."""
    now = 0.0
    for _ in range(steps):
        now += TIMESTEP_S
    return now


@pytest.mark.parametrize(
    "seconds",
    [0.0, _summed(10), _summed(500), _summed(30_010), 0.8200000000000006, 59.99999999, 3600.5],
)
def test_stamp_seconds_is_what_a_reader_computes_from_the_message(seconds: float) -> None:
    stamp = to_stamp(seconds)
    assert stamp_seconds(seconds) == stamp.sec + stamp.nanosec * 1e-9
