"""What an rclcpp node has that an rclpy node lacks: the parameter-events QoS parameters, and
a clean end on Ctrl-C whatever the node was doing."""

import time

from rcl_interfaces.msg import ParameterDescriptor
import rclpy

# rclcpp nodes declare these read-only parameters for their /parameter_events publisher; rclpy
# nodes do not, so the stand-in declares them with rclcpp's values and descriptions.
PARAMETER_EVENTS_QOS = (
    ('depth', 1000),
    ('durability', 'volatile'),
    ('history', 'keep_last'),
    ('reliability', 'reliable'),
)


def declare_parameter_events_qos(node):
    """Declare qos_overrides./parameter_events.publisher.* as an rclcpp node has them."""
    for policy, value in PARAMETER_EVENTS_QOS:
        name = f'qos_overrides./parameter_events.publisher.{policy}'
        if node.has_parameter(name):  # given at start-up (--params-file, -p)
            continue
        node.declare_parameter(
            name,
            value,
            ParameterDescriptor(
                description=f'qos policy {{{policy}}} for publisher {{/parameter_events}}',
                read_only=True,
            ),
        )


def shut_down_by_ctrl_c():
    """Return True once Ctrl-C has shut rclpy down (its signal thread may lag a moment)."""
    deadline = time.monotonic() + 1.0
    while rclpy.ok() and time.monotonic() < deadline:
        time.sleep(0.01)
    return not rclpy.ok()
