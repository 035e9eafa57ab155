"""What an rclcpp node has that an rclpy node lacks: the parameter-events QoS parameters."""

from rcl_interfaces.msg import ParameterDescriptor

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
