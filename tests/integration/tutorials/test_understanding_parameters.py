"""The Jazzy docs' "Understanding parameters" (turtlesim), typed as a learner types it.

Terminals as the tutorial opens them: turtlesim_node in one, turtle_teleop_key in another,
the `ros2 param` commands in a third. Outputs are the docs' where they show one, with what
real Jazzy adds (turtlesim 1.8's `holonomic`, rclpy's and rclcpp's
`start_type_description_service`).
"""

from __future__ import annotations

import re
import time
import urllib.request

# Real Jazzy's `ros2 param list` of the two nodes: the docs' list (written for Humble) plus
# turtlesim 1.8's holonomic and Jazzy's start_type_description_service.
PARAM_LIST = """\
/teleop_turtle:
  qos_overrides./parameter_events.publisher.depth
  qos_overrides./parameter_events.publisher.durability
  qos_overrides./parameter_events.publisher.history
  qos_overrides./parameter_events.publisher.reliability
  scale_angular
  scale_linear
  start_type_description_service
  use_sim_time
/turtlesim:
  background_b
  background_g
  background_r
  holonomic
  qos_overrides./parameter_events.publisher.depth
  qos_overrides./parameter_events.publisher.durability
  qos_overrides./parameter_events.publisher.history
  qos_overrides./parameter_events.publisher.reliability
  start_type_description_service
  use_sim_time
"""
DUMP = """\
/turtlesim:
  ros__parameters:
    background_b: 255
    background_g: 86
    background_r: 150
    holonomic: false
    qos_overrides:
      /parameter_events:
        publisher:
          depth: 1000
          durability: volatile
          history: keep_last
          reliability: reliable
    start_type_description_service: true
    use_sim_time: false

"""
# The docs' `ros2 param load` successes; the read-only ones fail with rclpy's reason (the
# course's turtlesim is an rclpy node; rclcpp words it "cannot be set because it is read-only").
LOAD_SUCCESSES = [
    f"Set parameter {name} successful"
    for name in ("background_b", "background_g", "background_r", "use_sim_time")
]
READ_ONLY = [
    f"qos_overrides./parameter_events.publisher.{p}"
    for p in ("depth", "durability", "history", "reliability")
]
WINDOW = r"TurtleSim window \(the course's, in your browser\): (http://127\.0\.0\.1:\d+/)\n"
SPAWNED = r"\[turtlesim\]: Spawning turtle \[turtle1\] at x=\[5\.544445\], y=\[5\.544445\]"


def _background(window: str) -> str:
    """Return the background colour the window's page draws now (its SVG)."""
    with urllib.request.urlopen(window + "view.svg", timeout=5) as reply:
        svg = reply.read().decode()
    return re.search(r'<rect id="background"[^>]* fill="([^"]+)"', svg).group(1)  # type: ignore[union-attr]


def test_understanding_parameters_runs_as_written(terminals) -> None:
    began = time.monotonic()
    sim, teleop, cli = terminals(), terminals(), terminals()
    assert cli.type("source /opt/ros/jazzy/setup.bash") == (
        "ROS 2 jazzy is already set up in this lab's terminal (ROS_DISTRO=jazzy): nothing to"
        " source.\n",
        0,
    )
    started = sim.start("ros2 run turtlesim turtlesim_node")
    window = sim.wait_for(WINDOW, started).group(1)  # what the learner opens in the browser
    sim.wait_for(r"Starting turtlesim with node name /turtlesim", started)
    sim.wait_for(SPAWNED)
    assert _background(window) == "rgb(69,86,255)"
    teleop.wait_for(r"'Q' to quit\.", teleop.start("ros2 run turtlesim turtle_teleop_key"))

    assert cli.type("ros2 param list") == (PARAM_LIST, 0)
    for channel, value in (("g", 86), ("r", 69), ("b", 255)):
        assert cli.type(f"ros2 param get /turtlesim background_{channel}") == (
            f"Integer value is: {value}\n",
            0,
        )
    assert cli.type("ros2 param set /turtlesim background_r 150") == (
        "Set parameter successful\n",
        0,
    )
    # The docs: "the background of the turtlesim window changes color" (the view's next draw).
    assert _background(window) == "rgb(150,86,255)"
    assert cli.type("ros2 param dump /turtlesim > turtlesim.yaml") == ("", 0)
    assert cli.type("cat turtlesim.yaml") == (DUMP, 0)
    loaded, code = cli.type("ros2 param load /turtlesim turtlesim.yaml")
    assert code == 0
    lines = loaded.splitlines()
    assert [line for line in lines if line in LOAD_SUCCESSES] == LOAD_SUCCESSES, loaded
    for name in READ_ONLY:
        assert any(line.startswith(f"Set parameter {name} failed: ") for line in lines), loaded

    # the arrow keys drive turtle1: the teleop node publishes on /turtle1/cmd_vel
    echo = terminals()
    start = echo.start("ros2 topic echo --once /turtle1/cmd_vel")
    echo.wait_for(r"Subscribed|^", start, 5)
    deadline = time.monotonic() + 20
    while "linear:" not in echo.output[start:] and time.monotonic() < deadline:
        teleop.send("\x1b[A")  # the up arrow, until the subscription has matched
        echo._read(0.3)
    echo.wait_for(r"linear:\n  x: 2\.0\n  y: 0\.0\n  z: 0\.0\nangular:\n  x: 0\.0", start, 5)

    # restart turtlesim with the saved parameters
    assert sim.interrupt()[1] == 0, sim.output[-3000:]  # the node's own last words
    restarted = sim.start(
        "ros2 run turtlesim turtlesim_node --ros-args --params-file turtlesim.yaml"
    )
    sim.wait_for(SPAWNED, restarted)
    assert cli.type("ros2 param get /turtlesim background_r") == ("Integer value is: 150\n", 0)
    assert _background(sim.wait_for(WINDOW, restarted).group(1)) == "rgb(150,86,255)"
    teleop.send("q")
    assert teleop.type("true")[1] == 0
    assert sim.interrupt()[1] == 0, sim.output[-3000:]  # the node's own last words
    print(f"Understanding parameters: {time.monotonic() - began:.1f} s")
