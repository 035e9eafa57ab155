"""Greet with `my_parameter` every second, then set it back to 'world'."""
import rclpy
from rclpy.node import Node
from rclpy.parameter import Parameter


class GreetingNode(Node):
    """The tutorial's `minimal_param_node`."""

    def __init__(self):
        super().__init__('minimal_param_node')
        self.declare_parameter('my_parameter', 'world')
        self.greeting_timer = self.create_timer(1.0, self.greet)

    def greet(self):
        name = self.get_parameter('my_parameter').value
        self.get_logger().info(f'Hello {name}!')
        self.set_parameters([Parameter('my_parameter', Parameter.Type.STRING, 'world')])


def main():
    rclpy.init()
    rclpy.spin(GreetingNode())


if __name__ == '__main__':
    main()
