"""Log each change of an_int_param (here) and of parameter_blackboard's a_double_param."""
import rclpy
from rclpy.node import Node
from rclpy.parameter import parameter_value_to_python
from rclpy.parameter_event_handler import ParameterEventHandler


class WatchingNode(Node):
    """The tutorial's `node_with_parameters`."""

    def __init__(self):
        super().__init__('node_with_parameters')
        self.declare_parameter('an_int_param', 0)
        self.events = ParameterEventHandler(self)
        self.watches = [
            self.events.add_parameter_callback(
                parameter_name=parameter, node_name=node, callback=self.report
            )
            for parameter, node in (
                ('an_int_param', 'node_with_parameters'),
                ('a_double_param', 'parameter_blackboard'),
            )
        ]

    def report(self, parameter):
        value = parameter_value_to_python(parameter.value)
        self.get_logger().info(f'Received an update to parameter: {parameter.name}: {value}')


def main():
    rclpy.init()
    rclpy.spin(WatchingNode())
