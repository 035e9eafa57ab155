"""The course's rclpy nodes end with exit code 0 when Ctrl-C lands while a callback publishes.

On SIGINT, rclpy's signal handler wakes a thread of its own that shuts the node's context down,
while the main thread may be running a callback. A `publish` in that callback then raises
`RCLError: publisher's context is invalid`, which left `rclpy.spin` and ended the node with
exit code 1 and a traceback (turtlesim_node in a tutorial's terminal, descriptor_vel in lesson
11; under load, 8 of 52 Ctrl-C stops of turtlesim_node). Here a timer added to each node does
what that thread does, at the worst moment: it shuts the context down, then publishes.

Ctrl-C may also land while rclpy turns a message it takes into Python: the KeyboardInterrupt
raised there comes out of `take_message` as "RuntimeError: Unable to convert call argument
'0' to Python object", before that thread (which needs the GIL) has shut anything down
(turtlesim_node, 1 of 20-40 Ctrl-C stops under a flood of messages; none of 60 since the
nodes wait up to a second for that thread).
"""

from __future__ import annotations

import sys
from collections.abc import Iterator

import pytest

from course_lib.session.session import Session, get_session

pytestmark = [pytest.mark.ros]

# Each program runs a node's own main() with a probe added to the node (`add_probe(node)`).
_NODE = """
import importlib, os, sys, threading

silent, kept_open = os.pipe()  # a stdin that stays quiet (the teleop loop waits on keys)
os.dup2(silent, 0)

module = importlib.import_module(sys.argv[1])
node_class = getattr(module, sys.argv[2])
build = node_class.__init__
"""
_MAIN = """
def build_with_probe(self, *args, **kwargs):
    build(self, *args, **kwargs)
    add_probe(self)

node_class.__init__ = build_with_probe
sys.argv[1:] = ['--ros-args', '--log-level', sys.argv[3] + ':=debug']  # the node's own log only
sys.exit(module.main())
"""


def _program(probe: str) -> str:
    """Return a program that runs a node's main() with the probe `probe` defines."""
    return _NODE + probe + _MAIN


# A timer that shuts the context down under its own publish.
SHUT_DOWN_MID_PUBLISH = _program("""
from std_msgs.msg import Empty

def add_probe(node):
    probe = node.create_publisher(Empty, 'ctrl_c_probe', 1)

    def ctrl_c_mid_publish():
        print('Shutting the context down under a publish', flush=True)
        node.context.shutdown()  # what rclpy's signal thread does on Ctrl-C
        probe.publish(Empty())

    node.create_timer(0.3, ctrl_c_mid_publish)
""")

# A probe message that Ctrl-C interrupts while rclpy builds it; rclpy's signal thread shuts
# the context down 0.2 s later (it is a race: here, a late one).
CTRL_C_MID_TAKE = _program("""
from std_msgs.msg import String

build_string = String.__init__
nodes = []

def build_string_with_ctrl_c(self, *args, **kwargs):
    build_string(self, *args, **kwargs)
    if sys._getframe(1).f_code.co_name == '_take_subscription':  # rclpy takes the probe's
        print('Ctrl-C while rclpy takes a message', flush=True)
        threading.Timer(0.2, nodes[0].context.try_shutdown).start()  # rclpy's signal thread
        raise KeyboardInterrupt  # what Python's SIGINT handler raises where the signal lands

String.__init__ = build_string_with_ctrl_c

def add_probe(node):
    nodes.append(node)
    probe = node.create_publisher(String, 'ctrl_c_probe', 1)
    node.create_subscription(String, 'ctrl_c_probe', lambda message: None, 1)
    node.create_timer(0.3, lambda: probe.publish(String(data='probe')))
""")

NODES = {  # executable: (module, node class, node name)
    "param_vel": ("parameter_tests.parameter_tests_node", "VelParam", "param_vel_node"),
    "descriptor_vel": (
        "parameter_descriptors.descriptor_vel_node", "DescriptorVel", "descriptor_vel_node"
    ),
    "turtlesim_node": ("turtlesim_rclpy.turtlesim_node", "Turtlesim", "turtlesim"),
    "parameter_blackboard": (
        "demo_nodes_cpp.parameter_blackboard", "ParameterBlackboard", "parameter_blackboard"
    ),
    "turtle_teleop_key": ("turtlesim_rclpy.turtle_teleop_key", "TeleopTurtle", "teleop_turtle"),
}  # fmt: skip


@pytest.fixture(scope="module")
def session() -> Iterator[Session]:
    session = get_session()
    yield session
    session.close()


CASES = {  # what the probe does: (its program, the line it prints, what the node then logs)
    "shutdown mid publish": (
        SHUT_DOWN_MID_PUBLISH,
        "Shutting the context down",
        'Ctrl-C ended a running callback: RCLError("Failed to publish:',
    ),
    "Ctrl-C mid take": (
        CTRL_C_MID_TAKE,
        "Ctrl-C while rclpy takes",
        "Ctrl-C ended a running callback: RuntimeError(",
    ),
}


@pytest.mark.parametrize("case", list(CASES))
@pytest.mark.parametrize("name", list(NODES))
def test_ctrl_c_under_a_running_callback_ends_the_node_cleanly(
    session: Session, name: str, case: str
) -> None:
    module, node_class, node_name = NODES[name]
    program, probe_line, caught = CASES[case]
    node = session.spawn([sys.executable, "-c", program, module, node_class, node_name], name=name)
    assert node.wait_for_line(probe_line, 30.0) is not None, node.text()
    code = node.wait(30.0)
    assert (code, "Traceback" in node.text()) == (0, False), node.text()
    assert caught in node.text(), node.text()  # what it caught is in its debug log
