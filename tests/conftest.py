"""Fixtures shared by the whole suite."""

from __future__ import annotations

import os
from collections.abc import Iterator

import pytest

from course_lib.core.paths import REPO_ROOT
from course_lib.session.session import Session

RERUNS_FILE = REPO_ROOT / "test-artifacts" / "reruns.txt"
_RERUN_TAIL = 40  # lines of each rerun's failure shown at the end of the run


def pytest_sessionstart(session: pytest.Session) -> None:
    if "PYTEST_XDIST_WORKER" not in os.environ:
        RERUNS_FILE.unlink(missing_ok=True)


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Never rerun a notebook's cell: a rerun runs it alone in a fresh kernel, without the
    cells before it (CI saw lesson 2's self-check fail with "name 'lesson' is not defined"
    after its cell 5 was rerun), which hides the first failure behind a false one."""
    from nbval.plugin import IPyNbCell

    for item in items:
        if isinstance(item, IPyNbCell):
            item.add_marker(pytest.mark.flaky(reruns=0))


def pytest_runtest_logreport(report: pytest.TestReport) -> None:
    """Keep why a test was rerun (a rerun is a flake to fix; -rR names it, never says why)."""
    if report.outcome != "rerun" or "PYTEST_XDIST_WORKER" in os.environ:
        return  # the workers' reports reach the controller, which writes them once
    RERUNS_FILE.parent.mkdir(parents=True, exist_ok=True)
    with RERUNS_FILE.open("a", encoding="utf-8") as out:
        out.write(f"===== {report.nodeid} ({report.when})\n{report.longreprtext}\n")


def pytest_terminal_summary(terminalreporter: pytest.TerminalReporter) -> None:
    if "PYTEST_XDIST_WORKER" in os.environ or not RERUNS_FILE.exists():
        return
    terminalreporter.section("why tests were rerun (the end of each failure)")
    for block in RERUNS_FILE.read_text(encoding="utf-8").split("===== ")[1:]:
        lines = block.splitlines()
        terminalreporter.write_line("===== " + lines[0])
        for line in lines[1:][-_RERUN_TAIL:]:
            terminalreporter.write_line(line)


@pytest.fixture(scope="module")
def session() -> Iterator[Session]:
    """Yield a course session with its own ROS domain for one test module."""
    course_session = Session()
    try:
        yield course_session
    finally:
        course_session.close()
