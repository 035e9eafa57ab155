"""How fast faults clear: a SIGKILLed kernel's processes, a stopped or crashed node's parameters.

Run: .venv/bin/python -m bench.fault_timing
A node stopped with SIGTERM says goodbye on DDS; one killed with SIGKILL (a crash) stays listed
until its DDS lease runs out (the course's Fast DDS profile sets the lease).
"""

from __future__ import annotations

import signal
import time

from course_lib.notebook.magics import run_line
from course_lib.session.session import get_session


def _listed() -> bool:
    return "/param_vel_node:" in run_line("param list").output.stdout


def _until(predicate, timeout: float) -> float:  # type: ignore[no-untyped-def]
    start = time.monotonic()
    while not predicate():
        if time.monotonic() - start > timeout:
            return float("inf")
        time.sleep(0.01)
    return time.monotonic() - start


def main() -> None:
    session = get_session()
    try:
        for sig, label in ((signal.SIGTERM, "stopped (SIGTERM)"), (signal.SIGKILL, "crashed")):
            node = session.run("parameter_tests", "param_vel")
            assert _until(_listed, 15) < 15, "param_vel_node never appeared"
            node.send_signal(sig)
            node.wait(5)
            gone = _until(lambda: not _listed(), 20)
            print(f"{'node ' + label + ' -> gone from `param list`':<48} {gone:7.2f} s")
    finally:
        session.close()


if __name__ == "__main__":
    main()
