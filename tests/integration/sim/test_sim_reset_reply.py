"""The simulation's reply to a reset reaches a subscription it had not matched when it replied.

Each side of a topic discovers the other on its own: a kernel's world handle can see the
simulation's reply publisher, and send its reset, before the simulation has matched the
handle's subscription. ci64's restarted world replied in that gap and the kernel waited in
vain ("the simulation did not reset within 5 s"). Here the subscription is made only after
the reply was sent: it must still receive it.
"""

from __future__ import annotations

import pytest
from std_msgs.msg import UInt32

from course_lib.core.waiting import wait_until
from course_lib.notebook import start_world
from course_lib.session.session import Session, SpinningNode
from course_lib.sim.ros.topics import RESET_DONE_TOPIC, RESET_TOPIC, reset_done_qos

pytestmark = [pytest.mark.ros, pytest.mark.sim]

NUMBER = 0x5EED


def test_a_reset_reply_reaches_a_subscription_made_after_it(session: Session) -> None:
    world = start_world(session, show=False)
    asker = SpinningNode(
        "reset_asker", domain_id=session.domain_id, owner="the test's", thread_name="asker"
    )
    heard: dict[str, list[int]] = {"early": [], "late": []}
    try:
        node = asker.node
        # a plain subscription matched before the reset: it tells when the reply has been sent
        node.create_subscription(
            UInt32, RESET_DONE_TOPIC, lambda msg: heard["early"].append(msg.data), 10
        )
        request = node.create_publisher(UInt32, RESET_TOPIC, 10)
        assert wait_until(lambda: request.get_subscription_count() > 0, 10.0)
        assert wait_until(lambda: node.count_publishers(RESET_DONE_TOPIC) > 0, 10.0)
        request.publish(UInt32(data=NUMBER))
        assert wait_until(lambda: NUMBER in heard["early"], 10.0), "the simulation never replied"
        node.create_subscription(
            UInt32, RESET_DONE_TOPIC, lambda msg: heard["late"].append(msg.data), reset_done_qos()
        )
        assert wait_until(lambda: NUMBER in heard["late"], 5.0), heard
    finally:
        asker.close()
        world.stop()
