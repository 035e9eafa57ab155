"""Fixtures shared by the whole suite."""

from __future__ import annotations

import gc
import os
import shutil
import signal
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from cpu_by_test import CpuMeter, read_records, record, summary
from file_order import file_of, longest_first, read_seconds, write_seconds
from host_speed import host_speed_line

from course_lib.core.paths import REPO_ROOT
from course_lib.ros2.node.direct import TEARDOWN_DUMPS_ENV
from course_lib.session.session import Session, close_current_session

if os.environ.get("COURSE_TRACE_ALLOCATIONS"):  # e.g. 25: frames kept; slow, so asked for
    import tracemalloc  # an unclosed socket's warning then says where it was made

    tracemalloc.start(int(os.environ["COURSE_TRACE_ALLOCATIONS"]))

# COURSE_FILE_SECONDS=tests/file_seconds.txt: write how long each file took (the order's data)
_SECONDS_OUT = os.environ.get("COURSE_FILE_SECONDS", "")
_file_seconds: dict[str, float] = {}
RERUNS_FILE = REPO_ROOT / "test-artifacts" / "reruns.txt"
_RERUN_TAIL = 40  # lines of each rerun's failure shown at the end of the run
# Set by the run that keeps RERUNS_FILE, for its workers and for the pytest runs its tests
# start (test_hub_attacks_own_network runs one, without PYTEST_* variables): each of those
# unlinked the file as it started, and the reason for ci54's one rerun was lost.
_RERUNS_KEPT_ENV = "COURSE_RERUNS_KEPT"
_keeps_reruns = False
# Each test's CPU, with every process it started (tests/harness/cpu_by_test.py), summed by file
# at the end of the run. The variable holds the pid of the run that owns the figures.
CPU_FOLDER = REPO_ROOT / "test-artifacts" / "cpu"
_CPU_OWNER_ENV = "COURSE_CPU_BY_TEST"
_meter: CpuMeter | None = None


def pytest_configure(config: pytest.Config) -> None:
    """Measure this process's tests: an xdist worker's, or a run's of its own (whose figures
    it starts afresh); a pytest run that a test starts is counted in that test."""
    global _meter
    if not hasattr(config, "workerinput"):
        if os.environ.get(_CPU_OWNER_ENV):
            return
        os.environ[_CPU_OWNER_ENV] = str(os.getpid())  # before xdist starts its workers
        shutil.rmtree(CPU_FOLDER, ignore_errors=True)
    _meter = CpuMeter()


def pytest_unconfigure() -> None:
    if _meter is not None:
        _meter.close()


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item: pytest.Item) -> Iterator[None]:
    if _meter is None or _meter.folder is None:
        yield
        return
    cpu, wall = _meter.seconds(), time.monotonic()
    yield
    record(CPU_FOLDER, item.nodeid, _meter.seconds() - cpu, time.monotonic() - wall)


@pytest.hookimpl(tryfirst=True)  # before xdist starts its workers, which inherit the variable
def pytest_sessionstart(session: pytest.Session) -> None:
    global _keeps_reruns
    if "PYTEST_XDIST_WORKER" in os.environ or os.environ.get(_RERUNS_KEPT_ENV):
        return
    os.environ[_RERUNS_KEPT_ENV] = "1"
    _keeps_reruns = True
    RERUNS_FILE.unlink(missing_ok=True)


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Deal the longest files first, those that wait for the learners' environment after each
    worker's first (tests/harness/file_order.py). Never rerun a notebook's
    cell: a rerun runs it alone in a fresh kernel, without the cells before it (CI saw lesson
    2's self-check fail with "name 'lesson' is not defined" after its cell 5 was rerun), which
    hides the first failure behind a false one."""
    from nbval.plugin import IPyNbCell

    late = {file_of(item.nodeid) for item in items if item.get_closest_marker("learners_env")}
    workers = int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1"))
    items[:] = longest_first(items, read_seconds(), late=late, workers=workers)
    for item in items:
        if isinstance(item, IPyNbCell):
            item.add_marker(pytest.mark.flaky(reruns=0))


def pytest_runtest_logreport(report: pytest.TestReport) -> None:
    """Keep why a test was rerun (a rerun is a flake to fix; -rR names it, never says why);
    add up each file's seconds when asked to record them."""
    if "PYTEST_XDIST_WORKER" in os.environ:
        return  # the workers' reports reach the controller, which writes them once
    if _SECONDS_OUT:
        name = file_of(report.nodeid)
        _file_seconds[name] = _file_seconds.get(name, 0.0) + report.duration
    if report.outcome != "rerun" or not _keeps_reruns:
        return
    RERUNS_FILE.parent.mkdir(parents=True, exist_ok=True)
    with RERUNS_FILE.open("a", encoding="utf-8") as out:
        out.write(f"===== {report.nodeid} ({report.when})\n{report.longreprtext}\n")


def pytest_sessionfinish(session: pytest.Session) -> None:
    if _meter is not None:  # what this process counted apart from its tests, as it stands
        for name, cpu, wall in _meter.apart():
            record(CPU_FOLDER, name, cpu, wall)
    if _SECONDS_OUT and "PYTEST_XDIST_WORKER" not in os.environ and _file_seconds:
        write_seconds(_file_seconds, Path(_SECONDS_OUT))


def pytest_terminal_summary(terminalreporter: pytest.TerminalReporter) -> None:
    if "PYTEST_XDIST_WORKER" in os.environ:
        return
    _report_teardowns_cut_short(terminalreporter)
    _report_cpu(terminalreporter)
    if not _keeps_reruns or not RERUNS_FILE.exists():
        return
    terminalreporter.section("why tests were rerun (the end of each failure)")
    for block in RERUNS_FILE.read_text(encoding="utf-8").split("===== ")[1:]:
        lines = block.splitlines()
        terminalreporter.write_line("===== " + lines[0])
        for line in lines[1:][-_RERUN_TAIL:]:
            terminalreporter.write_line(line)


def _report_cpu(terminalreporter: pytest.TerminalReporter) -> None:
    """Print the files whose tests used the most CPU, with every process they started."""
    if _meter is None or os.environ.get(_CPU_OWNER_ENV) != str(os.getpid()):
        return
    terminalreporter.section("CPU by test file (each test with every process it started)")
    lines = summary(read_records(CPU_FOLDER)) if CPU_FOLDER.is_dir() else []
    for line in lines or [f"not measured: {_meter.problem or 'no test ran'}"]:
        terminalreporter.write_line(line)
    if terminalreporter.config.getoption("numprocesses", None):  # a whole run (about 2 s)
        terminalreporter.write_line(host_speed_line())


def _report_teardowns_cut_short(terminalreporter: pytest.TerminalReporter) -> None:
    """Name the `ros2` commands whose teardown the watchdog cut short (exit code 1 after their
    output); drop the empty files of those that ended in time."""
    folder = os.environ.get(TEARDOWN_DUMPS_ENV)
    if not folder or not Path(folder).is_dir():
        return
    cut_short = []
    for dump in sorted(Path(folder).glob("teardown-*.txt")):
        if dump.stat().st_size:
            cut_short.append(dump)
        else:
            dump.unlink(missing_ok=True)
    if cut_short:
        terminalreporter.section("ros2 commands whose teardown was cut short")
        for dump in cut_short:
            terminalreporter.write_line(str(dump))


def _sigint_disposition() -> str:
    """Return whether this process ignores SIGINT and this thread blocks it (from /proc: what
    children inherit, whoever set it, Python or C)."""
    status = Path(f"/proc/self/task/{threading.get_native_id()}/status").read_text()
    fields = dict(line.split(":", 1) for line in status.splitlines() if ":" in line)
    bit = 1 << (signal.SIGINT - 1)
    ignored = int(fields["SigIgn"], 16) & bit
    blocked = int(fields["SigBlk"], 16) & bit
    return f"SIGINT ignored={bool(ignored)} blocked={bool(blocked)}"


# A shell without job control starts background commands (`make test &`) with SIGINT ignored,
# and every child inherits that: the Ctrl-C tests' commands would never see their Ctrl-C.
# The suite's processes take SIGINT as a terminal gives it (Python's default handler).
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)
_SIGINT_AT_START = _sigint_disposition()


@pytest.fixture(autouse=True)
def _sigint_left_alone() -> Iterator[None]:
    """Fail where SIGINT became ignored or blocked in the test process (a test, or the module
    fixtures set up before it): every child started afterwards inherits it, and Ctrl-C tests
    fail far from the cause."""
    before = _sigint_disposition()
    assert before == _SIGINT_AT_START, f"SIGINT changed before this test: {before}"
    yield
    after = _sigint_disposition()
    assert after == before, f"this test changed the test process's SIGINT: {before} -> {after}"


@pytest.fixture(scope="module", autouse=True)
def _garbage_of_the_module() -> Iterator[None]:
    """Collect what a test module left unreferenced as it ends: an object it never closed (an
    "unclosed socket") then fails that module's last test, not whichever test of another
    module the garbage collector happens to run in."""
    yield
    gc.collect()


@pytest.fixture(scope="module", autouse=True)
def _session_of_the_module() -> Iterator[None]:
    """Close this worker's session (`get_session()`) as a module ends, before the garbage is
    collected: its nodes stop with it. A module that left its node running handed it to the
    next module of the same worker ("nothing running" then listed param_vel_node's services:
    test_self_checks_fail before test_ros2_part2_empty)."""
    yield
    close_current_session()


@pytest.fixture(autouse=True)
def _terminals_closed() -> Iterator[None]:
    """Close the test terminals a test opened and left open, in that test (a socket freed
    later by the garbage collector fails whichever test runs then: "unclosed socket"); those
    of its module's fixtures stay open for the module's other tests."""
    module = sys.modules.get("lab_terminal")
    before = module.open_terminals() if module is not None else set()
    yield
    module = sys.modules.get("lab_terminal")
    if module is not None:
        module.close_terminals(module.open_terminals() - before)


@pytest.fixture(scope="module")
def session() -> Iterator[Session]:
    """Yield a course session with its own ROS domain for one test module."""
    course_session = Session()
    try:
        yield course_session
    finally:
        course_session.close()
