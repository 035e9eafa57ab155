"""The robot's samples reach every reader of a kernel through one subscription
(sim.view.samples_feed): the speed plot and the replay log (and the world handle) used to
take and decode each message once each, and the kernel's ROS thread woke once per reader."""

from __future__ import annotations

import logging
import time
from typing import Any

import pytest
from std_msgs.msg import Float64MultiArray

from course_lib.core.waiting import wait_until
from course_lib.notebook.widgets import SpeedPlot
from course_lib.session.session import Session
from course_lib.sim.view.run_log import RunLog
from course_lib.sim.view.samples_feed import samples_feed
from course_lib.sim.world.samples import FIELDS, SAMPLES_TOPIC

pytestmark = pytest.mark.ros


def _subscriptions(session: Session) -> int:
    """Count this session's node's subscriptions to the samples topic, as the graph has them."""
    name = session.node.get_name()
    infos = session.node.get_subscriptions_info_by_topic(SAMPLES_TOPIC)
    return sum(info.node_name == name for info in infos)


def _samples(stamp_s: float, count: int = 5) -> Float64MultiArray:
    rows = [
        dict.fromkeys(FIELDS, 0.0) | {"time_s": stamp_s + i * 0.02, "qw": 1.0, "linear_mps": 0.2}
        for i in range(count)
    ]
    return Float64MultiArray(data=[value for row in rows for value in row.values()])


def test_the_plot_and_the_log_share_one_subscription(
    session: Session, caplog: pytest.LogCaptureFixture
) -> None:
    plot = SpeedPlot(session)
    log = RunLog(session, fps=50)  # every sample 0.02 s apart kept
    failing: list[Any] = []

    def broken(samples: list[Any]) -> None:
        failing.append(samples)
        raise RuntimeError("a reader's own bug")

    feed = samples_feed(session)
    feed.add(broken)  # first: its error must not keep the others from their samples
    publisher = session.node.create_publisher(Float64MultiArray, SAMPLES_TOPIC, 10)
    try:
        assert wait_until(lambda: _subscriptions(session) >= 1, 10.0)
        time.sleep(0.5)  # a second subscription, if any, is in the graph by now
        assert _subscriptions(session) == 1
        assert wait_until(lambda: publisher.get_subscription_count() > 0, 10.0)
        with caplog.at_level(logging.ERROR):
            publisher.publish(_samples(1.0))
            assert wait_until(lambda: len(log.samples) == 5 and len(plot.samples) == 5, 10.0)
        assert len(failing) == 1
        assert "a reader of the robot's samples failed" in caplog.text

        feed.remove(broken)
        plot.close()
        assert _subscriptions(session) == 1  # the log still reads
        log.close()
        assert wait_until(lambda: _subscriptions(session) == 0, 10.0)
        assert feed.listeners == 0
    finally:
        session.node.destroy_publisher(publisher)
