"""From a command to the speed change seen on /odom: /cmd_vel directly, and the tutorial's way
(`param set /param_vel_node velocity 0.2`, which the node publishes on /cmd_vel every 0.1 s)."""

from __future__ import annotations

import statistics
import threading
import time
from typing import Any

from course_lib.notebook import World, start_world
from course_lib.session.session import Session

RUNS = 10
CHANGED_MPS = 0.02  # the first /odom reading clearly off its previous speed


def _time_to_change(world: World, target: float, act: Any) -> float:
    before = world.odom().linear_mps
    seen = threading.Event()
    stamp: list[float] = []

    def listener(msg: Any) -> None:
        if not seen.is_set() and abs(msg.twist.twist.linear.x - before) > CHANGED_MPS:
            stamp.append(time.monotonic())
            seen.set()

    world._listeners.append(listener)
    try:
        start = time.monotonic()
        act(target)
        if not seen.wait(5.0):
            raise TimeoutError("no speed change on /odom within 5 s")
        return stamp[0] - start
    finally:
        world._listeners.remove(listener)


def _settle(world: World, target: float) -> None:
    world.wait_for_odom(lambda r: abs(r.linear_mps - target) < 0.005, timeout=5.0)


def cmd_vel_latency(world: World) -> list[float]:
    """Publish /cmd_vel alternately 0.2 and 0.0; return the delays."""
    delays = []
    for run in range(RUNS):
        target = 0.2 if run % 2 == 0 else 0.0
        delays.append(_time_to_change(world, target, lambda v: world.drive(v, 0.0)))
        _settle(world, target)
    return delays


def param_latency(session: Session, world: World) -> list[float]:
    """Set param_vel_node's velocity alternately 0.2 and 0.0; return the delays."""
    from rclpy.parameter import Parameter
    from rclpy.parameter_client import AsyncParameterClient

    node = session.run("parameter_tests", "param_vel")
    client = AsyncParameterClient(session.node, "/param_vel_node")
    if not client.wait_for_services(timeout_sec=10.0):
        raise TimeoutError("param_vel_node did not answer")

    def set_velocity(value: float) -> None:
        future = client.set_parameters([Parameter("velocity", value=value)])
        session.wait_future(future, 5.0)

    delays = []
    try:
        _time_to_change(world, 0.1, set_velocity)  # warm-up: its /cmd_vel is discovered by now
        set_velocity(0.0)
        _settle(world, 0.0)
        for run in range(RUNS):
            target = 0.2 if run % 2 == 0 else 0.0
            delays.append(_time_to_change(world, target, set_velocity))
            _settle(world, target)
    finally:
        node.stop()
    return delays


def _report(label: str, delays: list[float]) -> None:
    ms = sorted(1000 * d for d in delays)
    print(
        f"{label}: median {statistics.median(ms):5.0f} ms, max {ms[-1]:5.0f} ms "
        f"(goal < 250 ms; {len(ms)} runs)"
    )


def main() -> None:
    session = Session()
    try:
        world = start_world(session, show=False)
        _report("cmd_vel -> speed change on /odom       ", cmd_vel_latency(world))
        world.drive(0.0, 0.0)
        _report("param set velocity -> change on /odom  ", param_latency(session, world))
    finally:
        session.close()


if __name__ == "__main__":
    main()
