"""demo_nodes_cpp's parameter_blackboard, in rclpy: a node that holds any parameter it is given.

The real node (C++) is an rclcpp node with allow_undeclared_parameters and
automatically_declare_parameters_from_overrides; so is this one, and it logs the same line.
"""

import time

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node

from .rclcpp_like import declare_parameter_events_qos


class ParameterBlackboard(Node):
    """Accept every parameter set on it, declared or not."""

    def __init__(self):
        super().__init__(
            'parameter_blackboard',
            allow_undeclared_parameters=True,
            automatically_declare_parameters_from_overrides=True,
        )
        declare_parameter_events_qos(self)
        # rclcpp adds start_type_description_service after the constructor has logged
        served = len(self._parameters) - 1
        self.get_logger().info(
            'Parameter blackboard node named \'%s\' ready, and serving \'%d\' parameters already!'
            % (self.get_fully_qualified_name(), served)
        )


def _shut_down_by_ctrl_c():
    """Return True once Ctrl-C has shut rclpy down (its signal thread may lag a moment)."""
    deadline = time.monotonic() + 1.0
    while rclpy.ok() and time.monotonic() < deadline:
        time.sleep(0.01)
    return not rclpy.ok()


def main(args=None):
    rclpy.init(args=args)
    node = ParameterBlackboard()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    except Exception as error:
        if not _shut_down_by_ctrl_c():
            raise
        # Ctrl-C: rclpy's signal thread shut the context down under a running callback
        node.get_logger().debug(f'Ctrl-C ended a running callback: {error!r}')
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == '__main__':
    main()
