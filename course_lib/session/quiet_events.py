"""Event settings for the course's own topics: no QoS event handlers.

rclpy gives every subscription and publisher default handlers (incompatible QoS, incompatible
type) unless told otherwise: two waitables each, which the executor adds to its wait set, in
Python, at every wake. A kernel's client node had 12 of them beside its 4 subscriptions, and
woke ten times a second for the robot's samples. The course owns both ends of its hidden
topics (the samples, the reset, the parameter-event journal), so a warning about their QoS
could only name a defect of the course, which its tests would find.
"""

from __future__ import annotations

from rclpy.event_handler import PublisherEventCallbacks, SubscriptionEventCallbacks

__all__ = ["quiet_publisher", "quiet_subscription"]


def quiet_subscription() -> SubscriptionEventCallbacks:
    """Return event callbacks that make a subscription no event handler."""
    return SubscriptionEventCallbacks(use_default_callbacks=False)


def quiet_publisher() -> PublisherEventCallbacks:
    """Return event callbacks that make a publisher no event handler."""
    return PublisherEventCallbacks(use_default_callbacks=False)
