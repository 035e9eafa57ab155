"""What tracing parameter changes costs: ms added to a `param set` through each door, and bytes.

Run: .venv/bin/python -m bench.param_trace_cost
Each course door journals its request (the old values from the journal's tail, one locked
append) before the set; the kernel journals each /parameter_events message it hears.
Timed here: the magic, the panel and the Python API in this process with the journal on and
off, the terminal's `ros2` through its daemon (journal on: the daemon runs the same client
code), one append alone, and building a history from a full journal.
"""

from __future__ import annotations

import statistics
import time
import tracemalloc
from collections.abc import Callable
from contextlib import contextmanager
from pathlib import Path
from tempfile import TemporaryDirectory
from typing import Any

from course_lib.core import param_journal
from course_lib.notebook.history import build_history
from course_lib.notebook.magics import run_line
from course_lib.notebook.widgets.events import parameter_events
from course_lib.ros2.api import nodes_and_params as api
from course_lib.ros2.node.set_journal import SetJournal
from course_lib.session.session import get_session

RUNS = 30
NODE = "/param_vel_node"


@contextmanager
def _journal_off() -> Any:
    real = SetJournal.old_values, SetJournal.record_request, SetJournal.record_answer
    SetJournal.old_values = lambda self, node, names, writers: dict.fromkeys(names)  # type: ignore[method-assign]
    SetJournal.record_request = lambda self, node, values, old, writers: []  # type: ignore[method-assign]
    SetJournal.record_answer = lambda self, node, values, marks, results: None  # type: ignore[method-assign]
    try:
        yield
    finally:
        SetJournal.old_values, SetJournal.record_request, SetJournal.record_answer = real  # type: ignore[method-assign]


def _median_ms(action: Callable[[float], Any]) -> float:
    times = []
    for n in range(RUNS):
        start = time.perf_counter()
        action(0.01 * (n % 20))
        times.append((time.perf_counter() - start) * 1000)
    return statistics.median(times)


def _terminal(session: Any) -> Callable[[float], Any]:
    import io

    from course_lib.ros2.node.connect import connect_or_start, request

    def run(value: float) -> None:
        sock = connect_or_start(str(session.domain_id), session.env)
        out = io.StringIO()
        argv = ["param", "set", NODE, "velocity", str(value)]
        request(sock, argv, cwd=".", stdout=out, stderr=out)

    return run


def main() -> None:
    session = get_session()
    parameter_events(session)
    node = session.run("parameter_tests", "param_vel")
    node.wait_for_line(lambda _l: True, 10.0)
    api.client().wait_all_seen(timeout=5.0)
    from course_lib.notebook.widgets import ParameterPanel

    with TemporaryDirectory() as tmp:
        panel = ParameterPanel(NODE, save_path=Path(tmp) / "p.yaml", session=session)
        doors = {
            "%ros2 magic": lambda v: run_line(f"param set {NODE} velocity {v}"),
            "parameter panel": lambda v: panel.set("velocity", v),
            "Python API": lambda v: api.param_set(NODE, "velocity", float(v)),
        }
        print(f"median of {RUNS} `param set` (ms, under load):  journal off   on   added")
        for name, action in [*doors.items(), *doors.items()]:  # twice: order effects show
            action(0.0)  # warm the service clients
            with _journal_off():
                off = _median_ms(action)
            on = _median_ms(action)
            print(f"  {name:<16} {off:>26.1f} {on:>5.1f} {on - off:>6.1f}")
        terminal = _terminal(session)
        terminal(0.0)
        print(f"  terminal ros2 (daemon, journal on) {_median_ms(terminal):>11.1f}")
        panel.close()
    path = param_journal.journal_path(session.domain_id)
    records = param_journal.read_journal(session.domain_id)
    print(f"journal: {len(records)} records, {path.stat().st_size} bytes")
    start = time.perf_counter()
    for _ in range(200):
        param_journal.append(session.domain_id, {"t": "bench"})
    print(f"one append: {(time.perf_counter() - start) / 200 * 1e6:.0f} µs")
    full = records * max(1, param_journal.JOURNAL_MAX_BYTES // max(1, path.stat().st_size))
    tracemalloc.start()
    start = time.perf_counter()
    build_history(full, NODE)
    took = time.perf_counter() - start
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    print(f"history of a full journal ({len(full)} records): {took * 1000:.0f} ms, "
          f"peak {peak / 1e6:.1f} MB")  # fmt: skip
    node.stop()
    session.close()


if __name__ == "__main__":
    main()
