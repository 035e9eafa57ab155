"""World.stop() runs every tear-down step even when one fails."""

from __future__ import annotations

import pytest

from course_lib.config.simulation import load_simulation_settings
from course_lib.notebook.world import World
from course_lib.session.session import Session

pytestmark = pytest.mark.ros


def test_a_failing_destroy_skips_no_other(
    session: Session, monkeypatch: pytest.MonkeyPatch
) -> None:
    process = session.spawn(["sleep", "30"], name="not-a-simulation")
    world = World(session, load_simulation_settings(), process)
    node = session.node
    real_destroy = node.destroy_subscription
    calls = []

    def failing_destroy(subscription: object) -> bool:
        calls.append(subscription)
        if len(calls) == 1:
            raise RuntimeError("injected tear-down failure")
        return real_destroy(subscription)

    monkeypatch.setattr(node, "destroy_subscription", failing_destroy)
    world.stop()
    assert world._cmd not in list(node.publishers)
    assert world._reset not in list(node.publishers)
    assert world._reset_sub not in list(node.subscriptions)
    assert world._fresh not in list(node.publishers)
    assert not process.alive
