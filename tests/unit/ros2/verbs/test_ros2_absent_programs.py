"""`ros2 run` of a docs' program the course cannot run says so in one line, with what to use."""

from __future__ import annotations

import pytest

from course_lib.ros2.command.commands import run_collected


@pytest.mark.parametrize(
    ("argv", "closest"),
    [
        (["demo_nodes_cpp", "talker"], "ros2 topic pub /chatter"),
        (["demo_nodes_cpp", "listener"], "ros2 topic echo /chatter"),
        (["demo_nodes_cpp", "add_two_ints_server"], "parameter_blackboard"),
        (["turtlesim", "draw_square"], "ros2 run turtlesim turtlesim_node"),
        (["examples_rclcpp_minimal_publisher", "publisher_member_function"], "executables"),
        (["demo_nodes_py", "talker"], "ros2 topic pub /chatter"),
    ],
)
def test_run_of_a_program_the_course_lacks_names_the_closest(
    argv: list[str], closest: str
) -> None:
    out = run_collected(["run", *argv])
    assert out.exit_code == 1 and not out.stdout
    assert out.stderr.count("\n") == 1 and closest in out.stderr, out.stderr


def test_run_of_an_unknown_package_is_as_real_ros2() -> None:
    out = run_collected(["run", "no_such_package", "x"])
    assert (out.exit_code, out.stderr) == (1, "Package 'no_such_package' not found\n")
