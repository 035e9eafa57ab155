"""What one `set_parameters` of the course's client costs: wall time and service calls.

Run: .venv/bin/python -m bench.param_set_calls [--sets N]
A fresh session starts the tutorial node (param_vel) and its kernel's /parameter_events feed
(as a lesson does), then sets `velocity` N times (default 200) through one RosClient, as
every door does. Printed: the total and median time of a set, and the parameter-service
requests sent per set (counted at rclpy's `Client.call_async`), by service.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from collections import Counter
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from course_lib.core import param_journal
from course_lib.ros2.node.client import RosClient
from course_lib.ros2.values import ParamValue
from course_lib.session.session import Session

NODE = "/param_vel_node"


@contextmanager
def _counting(calls: Counter[str]) -> Iterator[None]:
    """Count every service request rclpy sends, by the service's last name part."""
    from rclpy.client import Client

    real = Client.call_async

    def call_async(self: Any, request: Any) -> Any:
        calls[self.srv_name.rsplit("/", 1)[-1]] += 1
        return real(self, request)

    Client.call_async = call_async  # type: ignore[method-assign]
    try:
        yield
    finally:
        Client.call_async = real  # type: ignore[method-assign]


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--sets", type=int, default=200)
    sets = parser.parse_args().sets
    from course_lib.notebook.widgets.events import parameter_events

    session = Session()
    try:
        parameter_events(session)  # a lesson's kernel journals the events it hears
        node = session.run("parameter_tests", "param_vel")
        client = RosClient(session.node, session.wait_future)
        assert client.services_ready(NODE, timeout=15.0), f"{NODE} never answered"
        calls: Counter[str] = Counter()
        times = []
        with _counting(calls):
            start = time.perf_counter()
            for i in range(sets):
                began = time.perf_counter()
                (result,) = client.set_parameters(NODE, [("velocity", ParamValue.of(i / 1000))])
                times.append(time.perf_counter() - began)
                assert result.successful, result.reason
            total = time.perf_counter() - start
        records = param_journal.read_journal(session.domain_id)
        mine = [r for r in records if r.get("t") == "set" and r.get("pid") == os.getpid()]
        right = [[3, 0.0], *([3, i / 1000] for i in range(sets - 1))]
        same = sum(r.get("old") == old for r, old in zip(mine, right, strict=False))
        print(f"{sets} sets: {total:.3f} s, median {statistics.median(times) * 1000:.2f} ms")
        print("requests per set: " + ", ".join(f"{k} {v / sets:.3f}" for k, v in calls.items()))
        print(f"journal: {len(mine)} set records, {same} with the right old value")
        client.close()
        node.stop()
    finally:
        session.close()


if __name__ == "__main__":
    main()
