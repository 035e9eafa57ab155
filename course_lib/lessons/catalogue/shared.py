"""What several lessons' self-checks and templated cells share (ROS imported inside functions).

A check takes the lesson object (`lessons/lesson.Lesson`) and reads only its public names.
"""

from __future__ import annotations

from typing import Any

from .spec import Check, LessonView, check

__all__ = [
    "cm",
    "namesakes",
    "node_names",
    "only_driver",
    "other_drivers",
    "own_node",
    "own_node_running",
    "velocity",
    "written_in",
]


def node_names() -> list[str]:
    """Return the full names of the nodes in the graph now."""
    from ...ros2.api import nodes_and_params as api

    return api.node_list()


def own_node(lesson: LessonView, executable: str = "param_vel") -> Any:
    """Return the process of `executable` this lesson started, or None (never another's)."""
    running = [c for c in lesson.session.children if c.name == executable]
    return running[-1] if running else lesson.started.get(executable)


def own_node_running(lesson: LessonView, executable: str = "param_vel") -> bool:
    """Return True if the process of `executable` this lesson started still runs."""
    child = own_node(lesson, executable)
    return child is not None and child.alive


def velocity(node: str = "/param_vel_node") -> float | None:
    """Return `node`'s velocity parameter now, or None if it does not answer."""
    from ...ros2.api import nodes_and_params as api

    try:
        return api.param_get(node, "velocity").value
    except Exception:
        return None


def namesakes(node: str) -> tuple[bool, list[str]]:
    """Return whether `node` is in the graph, and who holds it among live processes (named).

    A node that has just stopped may still be listed for a moment with no process behind it:
    wait (bounded by the discovery lease) until it leaves or a live process is seen holding it.
    """
    from ...core.waiting import wait_until
    from ...lab import drivers
    from ...lab.drivers import describe, publishers
    from ...ros2.api.nodes_and_params import client

    def settled() -> tuple[bool, list[str]] | None:
        listed = node in node_names()
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


def other_drivers(lesson: LessonView, executable: str) -> list[str]:
    """Return who else publishes on /cmd_vel than this lesson's `executable` (names, pids)."""
    from ...lab.drivers import describe
    from ...lab.drivers import other_drivers as others_of
    from ...lab.takeover import lessons_nodes
    from ...ros2.api.nodes_and_params import client

    own = own_node(lesson, executable)
    found = others_of(client(), own.pid if own and own.alive else None)
    records = lessons_nodes() if found else []
    named = []
    for publisher in found:
        starters = [r.label for r in records if publisher.runs_in(int(r.tag.split(":")[0]))]
        named.append(describe(publisher) + (f", started by {starters[0]}" if starters else ""))
    return named


def only_driver(lesson: LessonView, executable: str, node: str, others: list[str]) -> Check:
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
        own_node_running(lesson, executable) and not others,
        hint,
    )


def written_in(lesson: LessonView, path: Any) -> bool:
    """Return True if `path` was written since this lesson started (not by an earlier run)."""
    try:
        return path.stat().st_mtime >= lesson.started_at - 1.0  # file systems round mtimes
    except OSError:
        return False


def cm(metres: float) -> str:
    """Return a length in metres as the cells write it in centimetres ("5 cm")."""
    return f"{metres * 100:g} cm"
