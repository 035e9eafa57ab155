"""turtle_teleop_key in rclpy: arrow keys in a terminal drive turtle1, as the real one does."""

import os
import select
import sys
import termios
import tty

from geometry_msgs.msg import Twist
import rclpy
from rclpy.action import ActionClient
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from turtlesim.action import RotateAbsolute

from .rclcpp_like import declare_parameter_events_qos, shut_down_by_ctrl_c

ARROWS = {'A': (1.0, 0.0), 'B': (-1.0, 0.0), 'C': (0.0, -1.0), 'D': (0.0, 1.0)}
# The absolute headings (rad) of the rotation keys, as the real teleop sends them.
ROTATIONS = {
    'g': 0.0, 't': 0.7854, 'r': 1.5708, 'e': 2.3562,
    'd': 3.1416, 'c': -2.3562, 'v': -1.5708, 'b': -0.7854,
}
INSTRUCTIONS = (
    'Reading from keyboard\n'
    '---------------------------\n'
    'Use arrow keys to move the turtle.\n'
    "Use G|B|V|C|D|E|R|T keys to rotate to absolute orientations. 'F' to cancel a rotation.\n"
    "'Q' to quit.\n"
)


class TeleopTurtle(Node):
    """Publish a Twist on turtle1/cmd_vel for each arrow key."""

    def __init__(self):
        super().__init__('teleop_turtle')
        self.declare_parameter('scale_angular', 2.0)
        self.declare_parameter('scale_linear', 2.0)
        declare_parameter_events_qos(self)
        self.publisher = self.create_publisher(Twist, 'turtle1/cmd_vel', 1)
        self.rotate_absolute = ActionClient(self, RotateAbsolute, 'turtle1/rotate_absolute')
        self.goal_handle = None

    def on_key(self, key):
        """Act on one key (the last byte of an arrow's escape sequence); False to quit."""
        if key in ('q', 'Q'):
            return False
        if key.lower() in ROTATIONS:
            goal = RotateAbsolute.Goal(theta=ROTATIONS[key.lower()])
            self.rotate_absolute.send_goal_async(goal).add_done_callback(self.on_goal_response)
        elif key.lower() == 'f' and self.goal_handle is not None:
            self.goal_handle.cancel_goal_async()
        if key in ARROWS:
            linear, angular = ARROWS[key]
            msg = Twist()
            msg.linear.x = self.get_parameter('scale_linear').value * linear
            msg.angular.z = self.get_parameter('scale_angular').value * angular
            self.publisher.publish(msg)
        return True


    def on_goal_response(self, future):
        self.goal_handle = future.result()


def _key_loop(node, fd):
    while rclpy.ok():
        ready, _, _ = select.select([fd], [], [], 0.1)
        if ready:
            data = os.read(fd, 1)
            if not data or not node.on_key(data.decode(errors='replace')):
                return
        rclpy.spin_once(node, timeout_sec=0)



def main(args=None):
    rclpy.init(args=args)
    node = TeleopTurtle()
    fd = sys.stdin.fileno()
    saved = termios.tcgetattr(fd) if os.isatty(fd) else None
    sys.stdout.write(INSTRUCTIONS)
    sys.stdout.flush()
    try:
        if saved is not None:
            tty.setcbreak(fd)
        _key_loop(node, fd)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    except Exception as error:
        if not shut_down_by_ctrl_c():
            raise
        # Ctrl-C: rclpy's signal thread shut the context down under a running callback
        node.get_logger().debug(f'Ctrl-C ended a running callback: {error!r}')
    finally:
        if saved is not None:
            termios.tcsetattr(fd, termios.TCSADRAIN, saved)
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == '__main__':
    main()
