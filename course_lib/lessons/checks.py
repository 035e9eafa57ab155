"""Each lesson's self-check: look at the real nodes, files and robot, say what passed."""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

import yaml

from .report import Check, check

__all__ = ["installed_checks", "own_node", "run_checks"]

# Lesson 8's dump: the learner's own file (the package's params file is never rewritten).
DUMP_NAME = "dump/param_vel_node.yaml"
NODE_11 = "descriptor_vel_node"


def _nodes() -> list[str]:
    from ..ros2.api import nodes_and_params as api

    return api.node_list()


def own_node(lesson: Any, executable: str = "param_vel") -> Any:
    """Return the process of `executable` this lesson started, or None (never another's)."""
    running = [c for c in lesson.session.children if c.name == executable]
    return running[-1] if running else lesson.started.get(executable)


def _own_node_running(lesson: Any, executable: str = "param_vel") -> bool:
    child = own_node(lesson, executable)
    return child is not None and child.alive


def _velocity(node: str = "/param_vel_node") -> float | None:
    from ..ros2.api import nodes_and_params as api

    try:
        return api.param_get(node, "velocity").value
    except Exception:
        return None


def installed_checks(found: dict[str, str]) -> list[Check]:
    """Return lesson 1's checks of what is installed, from `environment.versions()`."""
    return [
        check("ROS 2 Jazzy's rclpy is installed", found["ROS 2 distro"] == "jazzy"),
        check(
            "MuJoCo and meshcat are installed",
            "missing" not in (found["MuJoCo"], found["meshcat"]),
            "run `make setup` in a terminal, then restart the kernel.",
        ),
    ]


def _lesson_1(lesson: Any) -> list[Check]:
    from ..core import ament
    from ..core.errors import CourseError
    from .environment import versions

    try:
        exes = ament.package_executables("parameter_tests", lesson.session.env)
    except CourseError:  # the package is not in the workspace at all
        exes = []
    return [
        *installed_checks(versions()),
        check(
            "your session talks ROS 2 in its own domain",
            not lesson.session.closed,
            "run the first cell again.",
        ),
        check(
            "the workspace is built: parameter_tests has param_vel",
            "param_vel" in exes,
            "run `make setup` in a terminal (it builds rosject/ with colcon).",
        ),
    ]


def _namesakes(node: str) -> tuple[bool, list[str]]:
    """Return whether `node` is in the graph, and who holds it among live processes (named).

    A node that has just stopped may still be listed for a moment with no process behind it:
    wait (bounded by the discovery lease) until it leaves or a live process is seen holding it.
    """
    from ..core.waiting import wait_until
    from ..lab import drivers
    from ..lab.drivers import describe, publishers
    from ..ros2.api.nodes_and_params import client

    def settled() -> tuple[bool, list[str]] | None:
        listed = node in _nodes()
        holders = [p for p in publishers(client()) if p.node == node and p.pids]
        return (listed, [describe(p) for p in holders]) if not listed or holders else None

    found = wait_until(settled, drivers.GONE_WAIT_S, interval=0.1)
    if found is not None:
        return found
    # Still listed, driving nothing: a ghost is not a running node. Every ROS node publishes its
    # parameter events; here no live process does (its processes are gone and its lease has not
    # run out in this kernel yet, or its name outlived its participant in the graph cache, as in
    # the real daemon: ros2/ros2#1413, seen for 8 s and more on a busy host).
    events = [p for p in publishers(client(), "/parameter_events") if p.node == node]
    return (False, []) if not any(p.pids for p in events) else (True, [])


def _lesson_2(lesson: Any) -> list[Check]:
    started = own_node(lesson) is not None
    gone = started and not _own_node_running(lesson)
    listed, others = _namesakes("/param_vel_node") if gone else (False, [])
    what = "param_vel_node is gone, and its parameters with it"
    if listed and others:  # yours is gone; another lesson's or a terminal's has the name
        what += f" (the one running now is another: {', '.join(others)}, with its own)"
    return [
        check(
            "you started param_vel_node in this lesson",
            started,
            "run the `%ros2 run parameter_tests param_vel` cell.",
        ),
        check(
            what,
            gone and (not listed or others),
            'run the cell with `lesson.stop("param_vel")`.',
        ),
    ]


def _lesson_3(lesson: Any) -> list[Check]:
    from ..ros2.api import nodes_and_params as api

    alive = lesson._world is not None and lesson._world.alive
    topics = {t.name for t in api.topic_list()} if alive else set()
    return [
        check("the simulation is running", alive, "run the cell with `lesson.world()`."),
        check(
            "the robot's topics /cmd_vel, /odom and /scan exist",
            {"/cmd_vel", "/odom", "/scan"} <= topics,
            "start the world, then list topics again.",
        ),
    ]


def _lesson_4(lesson: Any) -> list[Check]:
    from ..core import ament
    from ..core.errors import CourseError
    from ..launch.ros.declared import declared_parameters, node_sources

    try:  # the installed node the learner runs, not the file they may be editing
        exe = str(ament.find_executable("parameter_tests", "param_vel", lesson.session.env))
    except CourseError:
        exe = ""
    velocity = declared_parameters(exe).get("velocity") if exe else None
    sources = node_sources(exe) if exe else []
    source = sources[0].read_text(encoding="utf-8") if sources else ""
    return [
        check(
            "the node declares `velocity` as a double, default 0.0",
            velocity is not None and velocity.type == "double" and velocity.default == 0.0,
            "compare the declare_parameter line with the tutorial's; then `make setup`.",
        ),
        check("a 0.1 s timer publishes it", re.search(r"create_timer\(0\.1,", source) is not None),
    ]


def _lesson_5(lesson: Any) -> list[Check]:
    from ..ros2.api import nodes_and_params as api

    running = _own_node_running(lesson) and "/param_vel_node" in _nodes()
    speed = api.topic_echo_once("/cmd_vel").linear.x if running else None
    return [
        check("param_vel_node is running", running, "run the `%ros2 run` cell again."),
        check(
            "it publishes its velocity (0.0) on /cmd_vel",
            speed == 0.0,
            "is the node running? `%ros2 node list`",
        ),
    ]


def _lesson_6(lesson: Any) -> list[Check]:
    return [
        check(
            "param_vel_node, started in this lesson, answers: velocity is 0.0",
            _own_node_running(lesson) and _velocity() == 0.0,
            "start it with `%ros2 run parameter_tests param_vel`.",
        ),
    ]


def other_drivers(lesson: Any, executable: str) -> list[str]:
    """Return who else publishes on /cmd_vel than this lesson's `executable` (names, pids)."""
    from ..lab.drivers import describe
    from ..lab.drivers import other_drivers as others_of
    from ..lab.takeover import lessons_nodes
    from ..ros2.api.nodes_and_params import client

    own = own_node(lesson, executable)
    found = others_of(client(), own.pid if own and own.alive else None)
    records = lessons_nodes() if found else []
    named = []
    for publisher in found:
        starters = [r.label for r in records if publisher.runs_in(int(r.tag.split(":")[0]))]
        named.append(describe(publisher) + (f", started by {starters[0]}" if starters else ""))
    return named


def only_driver(lesson: Any, executable: str, node: str, others: list[str]) -> Check:
    """Check that this lesson's `executable` runs and nothing else publishes on /cmd_vel."""
    if others:
        verb = "publish" if len(others) > 1 else "publishes"
        hint = (
            f"{', '.join(others)} also {verb} on /cmd_vel: stop it (Ctrl-C in its terminal; "
            "a lesson's node: run this lesson's `%ros2 run` cell again, it stops the others), "
            "then run this cell again."
        )
    else:
        hint = f"start {node} with its `%ros2 run` cell."
    return check(
        f"only your {node} drives the robot (no other publisher on /cmd_vel)",
        _own_node_running(lesson, executable) and not others,
        hint,
    )


def _standing_still(lesson: Any) -> bool:
    """Return True if this lesson's robot stands still now (measured on /odom)."""
    world = lesson._world
    return world is not None and world.alive and abs(world.odom().linear_mps) < 0.005


def _lesson_7(lesson: Any) -> list[Check]:
    others = other_drivers(lesson, "param_vel")
    alone = only_driver(lesson, "param_vel", "param_vel_node", others)
    if others:  # the robot's motion is not only the learner's doing: judge nothing of it
        return [alone]
    target = lesson.velocity
    top = lesson.state.get("top_speed", 0.0)  # measured by this lesson's drive_for()
    return [
        alone,
        check(
            f"the robot drove at {target:g} m/s (measured on /odom)",
            abs(top - target) < 0.02,
            f"set velocity to {target:g}, then run the cell that waits in simulated time.",
        ),
        check(
            "velocity is back to 0.0 and the robot stopped",
            _own_node_running(lesson) and _velocity() == 0.0 and _standing_still(lesson),
            "`%ros2 param set /param_vel_node velocity 0.0`, then the cell after it.",
        ),
    ]


def _written_in(lesson: Any, path: Any) -> bool:
    """Return True if `path` was written since this lesson started (not by an earlier run)."""
    try:
        return path.stat().st_mtime >= lesson.started_at - 1.0  # file systems round mtimes
    except OSError:
        return False


def _lesson_8(lesson: Any) -> list[Check]:
    from ..ros2.api import nodes_and_params as api

    dump = lesson.learner_file(DUMP_NAME)
    try:
        if not _written_in(lesson, dump):
            raise OSError("written by an earlier run")
        text = dump.read_text(encoding="utf-8")
        value = yaml.safe_load(text)["/param_vel_node"]["ros__parameters"]["velocity"]
    except (OSError, yaml.YAMLError, KeyError, TypeError):
        text, value = None, None
    live = api.ros2("param dump /param_vel_node").stdout
    return [
        check(
            f"my_files/{DUMP_NAME} holds /param_vel_node's ros__parameters",
            isinstance(value, float),
            "run the cell that redirects the dump into the file.",
        ),
        check(
            "the file is exactly what `ros2 param dump` prints now",
            live == text,
            "dump again into the file.",
        ),
    ]


def _lesson_9(lesson: Any) -> list[Check]:
    from ..launch.command.dry_run import dry_run

    path = lesson.learner_file("param_vel_node.yaml")
    try:
        if not _written_in(lesson, path):
            raise OSError("written by an earlier run")
        value = yaml.safe_load(path.read_text())["/param_vel_node"]["ros__parameters"]["velocity"]
    except (OSError, yaml.YAMLError, KeyError, TypeError):
        value = None
    return [
        check(
            "your params file sets velocity: 0.3 (a double)",
            value == 0.3 and type(value) is float,
            "run the cells that copy and edit the file.",
        ),
        check(
            "a launch with it would start param_vel_node with velocity 0.3",
            value == 0.3 and _planned_velocity(dry_run, path) == 0.3,
            "run the cells that copy and edit the file.",
        ),
    ]


def _planned_velocity(dry_run: Any, path: Any) -> Any:
    try:
        report = dry_run(
            "parameter_tests", "test_parameters_file.launch.py", f"params_file:={path}"
        )
    except Exception:
        return None
    return report.nodes[0].values.get("velocity", (None,))[0] if report.nodes else None


def _lesson_10(lesson: Any) -> list[Check]:
    seen = lesson.state.get("launch_velocities", [])
    launches = lesson.state.get("launches", [])
    stopped = bool(launches) and not any(handle.alive for handle in launches)
    # a node that has just stopped may be listed a moment more, and another lesson's (or a
    # terminal's) param_vel_node is not this lesson's launch: judge only what this one started
    listed, others = _namesakes("/param_vel_node") if stopped else (True, [])
    what = "every launch was stopped (no param_vel_node left)"
    if listed and others:
        what += f" (the one running now is another: {', '.join(others)})"
    return [
        check("the Python launch file started param_vel_node with velocity 0.2", 0.2 in seen),
        check(
            what, stopped and (not listed or bool(others)), "run the cells that call `.stop()`."
        ),
    ]


def _lesson_11(lesson: Any) -> list[Check]:
    from ..core.errors import CourseError
    from ..ros2.api import nodes_and_params as api

    try:  # both must be refused by the running node itself, not fail for its absence
        rejected = api.param_set("/descriptor_vel_node", "velocity", 0.3)
        read_only = api.param_set("/descriptor_vel_node", "max_travel", 9.0)
    except CourseError:
        rejected = read_only = None
    running = "run the `%ros2 run parameter_descriptors descriptor_vel` cell."
    saved = lesson.state.get("saved_params")
    return [
        only_driver(lesson, "descriptor_vel", NODE_11, other_drivers(lesson, "descriptor_vel")),
        check(
            "the range refuses velocity 0.3 (max 0.26)",
            rejected is not None and not rejected.successful,
            running,
        ),
        check("max_travel is read-only", read_only is not None and not read_only.successful),
        check(
            "the panel saved a params file ROS can load",
            saved is not None and saved.exists(),
            "press the panel's save button (or run `panel.save(...)`).",
        ),
        check(
            "the travel exercise passed",
            lesson.state.get("exercise_passed", False),
            "change the two numbers of the exercise cell and run it and the check again.",
        ),
    ]


CHECKS: dict[int, Callable[[Any], list[Check]]] = {
    n: globals()[f"_lesson_{n}"] for n in range(1, 12)
}


def run_checks(lesson: Any) -> list[Check]:
    """Return lesson `lesson.number`'s checks, run now."""
    return CHECKS[lesson.number](lesson)
