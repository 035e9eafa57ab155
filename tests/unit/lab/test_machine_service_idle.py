"""The lab's machine service sleeps between requests and still stops at once."""

from __future__ import annotations

import threading
import time
from pathlib import Path

from course_lib.lab.client import MachineClient
from course_lib.lab.service import MachineService
from course_lib.processes.children import spawn


def _wakes(thread: threading.Thread) -> int:
    """Return how many times the kernel has run `thread` (schedstat's third field)."""
    with open(f"/proc/self/task/{thread.native_id}/schedstat") as stat:
        return int(stat.read().split()[2])


def test_an_idle_service_does_not_wake_and_stops_at_once(tmp_path: Path) -> None:
    service = MachineService(tmp_path / "lab.sock", spawn).start()
    try:
        assert MachineClient(service.path).request("ping", timeout=5.0)["ok"]
        served = next(t for t in threading.enumerate() if t.name == "course-machine")
        before = _wakes(served)
        time.sleep(2.0)
        # socketserver's serve_forever woke every 0.5 s to look for a shutdown: 3 or 4 here
        assert _wakes(served) - before <= 1
        assert MachineClient(service.path).request("ping", timeout=5.0)["ok"]  # still answers
    finally:
        started = time.monotonic()
        service.stop()
        took = time.monotonic() - started
    assert took < 1.0, f"stop() took {took:.2f} s"
    assert not served.is_alive()
    assert not service.path.exists()
