"""descriptor_vel_node's trip on simulated time: timed from the clock, not from before it ran.

A node started with `use_sim_time:=true` reads 0 s until its first /clock message (discovery
can take seconds on a busy host). A velocity set before then used to start a trip at 0 s that
the first tick, at the real simulated time, ended at once: the robot never moved.
"""

from __future__ import annotations

import time
from collections.abc import Iterator

import pytest

from course_lib.core.waiting import wait_until
from course_lib.ros2.api import nodes_and_params as api
from course_lib.session.session import Session, get_session

pytestmark = [pytest.mark.ros, pytest.mark.slow]

NODE = "/descriptor_vel_node"
CLOCK_START_S = 500.0  # the simulated time the clock starts at, as in a world left running


@pytest.fixture
def session() -> Iterator[Session]:
    session = get_session()
    yield session
    session.stop_children()


def test_a_trip_set_before_the_first_clock_message_drives_its_whole_time(
    session: Session,
) -> None:
    from builtin_interfaces.msg import Time
    from rosgraph_msgs.msg import Clock

    node = session.run(
        "parameter_descriptors", "descriptor_vel", "--ros-args", "-p", "use_sim_time:=true",
        "-p", "travel_time:=1.0",
    )  # fmt: skip
    assert node.wait_for_line("Ready", 10.0) is not None
    assert api.param_set(NODE, "velocity", 0.2).successful  # no /clock yet: the node reads 0 s
    clock = session.node.create_publisher(Clock, "/clock", 10)
    try:
        assert wait_until(lambda: clock.get_subscription_count() > 0, 10.0)
        velocities = []
        for tick in range(30):  # 3 s of simulated time at 10 Hz, on wall time
            now = CLOCK_START_S + tick * 0.1
            clock.publish(Clock(clock=Time(sec=int(now), nanosec=round(now % 1 * 1e9))))
            time.sleep(0.1)
            if tick in (5, 25):  # 0.5 s into the trip, and 1.5 s after its end
                velocities.append(api.param_get(NODE, "velocity").value)
    finally:
        session.node.destroy_publisher(clock)
    assert velocities == [0.2, 0.0], "the trip did not drive for its travel_time"
    assert "Trip of 1.0 s done, stopping" in node.text()
