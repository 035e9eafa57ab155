"""The suite deals its longest files first, and the files that mostly wait to a worker of
their own, from a table of measured seconds and CPU-seconds."""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace

import pytest
from file_order import (
    SECONDS_FILE,
    WAITING_LANE,
    FileFigures,
    deal_order,
    read_figures,
    scope_of,
    waiting_lane,
    write_figures,
)
from lane_scheduling import WaitingLaneScheduling

from course_lib.core.paths import REPO_ROOT
from course_lib.tools.suite import pytest_argv


@dataclass
class Item:
    nodeid: str


def test_the_longest_file_goes_first_and_a_file_keeps_its_tests_in_order() -> None:
    items = [Item(n) for n in ("a.py::t1", "b.py::t1", "a.py::t2", "c.py::t1", "d.py::t1")]
    ordered = deal_order(items, {"c.py": 60.0, "a.py": 5.0})
    assert [i.nodeid for i in ordered] == [
        "c.py::t1",
        "a.py::t1",
        "a.py::t2",
        "b.py::t1",
        "d.py::t1",
    ]


def test_every_file_the_table_names_exists() -> None:
    """A renamed or removed test file would silently lose its place at the front."""
    missing = [name for name in read_figures() if not (REPO_ROOT / name).is_file()]
    assert not missing, f"{SECONDS_FILE.name} names files that no longer exist: {missing}"


def test_the_table_puts_the_slowest_browser_walk_in_front() -> None:
    figures = read_figures()
    assert max(figures, key=lambda name: figures[name].seconds) == (
        "tests/browser/test_lab_full_walk.py"
    )


def test_a_written_table_reads_back_and_leaves_out_short_files(tmp_path: Path) -> None:
    path = tmp_path / "seconds.txt"
    write_figures({"a.py": 1.0, "b.py": 30.4, "c.py": 7.6}, {"b.py": 12.34, "a.py": 1.0}, path)
    # c.py's CPU was not measured: '-', and it never counts as a file that waits
    assert read_figures(path) == {"b.py": FileFigures(30.0, 12.3), "c.py": FileFigures(8.0)}
    assert not read_figures(path)["c.py"].waits


def test_a_bad_line_names_its_file_and_line(tmp_path: Path) -> None:
    path = tmp_path / "seconds.txt"
    path.write_text("# comment\n12 3.5 a.py\nslow 1.0 b.py\n", encoding="utf-8")
    with pytest.raises(ValueError, match=r"seconds.txt:3: expected 'SECONDS CPU-SECONDS FILE'"):
        read_figures(path)
    path.write_text("12 a.py\n", encoding="utf-8")  # the old table's line: no CPU
    with pytest.raises(ValueError, match=r"seconds.txt:1: expected"):
        read_figures(path)


def test_xdist_keeps_the_order() -> None:
    """xdist's own order (most tests first) would deal the long one-test files last."""
    assert "--no-loadscope-reorder" in pytest_argv([])


def _order(nodeids: list[str], seconds: dict[str, float], **kwargs: object) -> list[str]:
    return [i.nodeid for i in deal_order([Item(n) for n in nodeids], seconds, **kwargs)]


def test_a_file_that_waits_for_the_build_starts_after_a_workers_first_file() -> None:
    seconds = {"walk.py": 200.0, "hub.py": 150.0, "b.py": 100.0, "c.py": 90.0, "d.py": 50.0}
    nodeids = ["d.py::t", "c.py::t", "hub.py::t1", "b.py::t", "walk.py::t", "hub.py::t2"]
    assert _order(nodeids, seconds, late={"hub.py"}, workers=2) == [
        "walk.py::t",
        "b.py::t",
        "hub.py::t1",
        "hub.py::t2",
        "c.py::t",
        "d.py::t",
    ]
    # two that wait: neither takes the other's place in the first round
    assert _order(nodeids, seconds, late={"hub.py", "b.py"}, workers=2)[:2] == [
        "walk.py::t",
        "c.py::t",
    ]
    # already past the first round: its place is kept
    assert _order(nodeids, seconds, late={"d.py"}, workers=2) == _order(nodeids, seconds)
    # fewer files than workers: it goes last
    assert _order(["hub.py::t", "b.py::t"], seconds, late={"hub.py"}, workers=4) == [
        "b.py::t",
        "hub.py::t",
    ]


def test_every_file_with_a_class_hub_waits_for_the_learners_environment() -> None:
    """A hub's start waits for the learners' environment build; a file that starts one without
    the marker would be dealt first and stand idle for the build (ci95: 75 s)."""
    users = ("from class_hub import", "from hub_accounts import")
    unmarked = []
    for path in sorted((REPO_ROOT / "tests").rglob("test_*.py")):
        text = path.read_text(encoding="utf-8")
        starts_a_hub = any(line.startswith(users) for line in text.splitlines())
        if starts_a_hub and "pytest.mark.learners_env" not in text:
            unmarked.append(str(path.relative_to(REPO_ROOT)))
    assert not unmarked, (
        f"files that start a class hub without @pytest.mark.learners_env: {unmarked}"
    )


def test_the_files_that_wait_use_under_15_percent_of_a_core_and_go_longest_first() -> None:
    figures = {
        "walk.py": FileFigures(200.0, 100.0),  # uses the cores
        "drive.py": FileFigures(120.0, 12.0),  # a tenth of a core: waits
        "hz.py": FileFigures(60.0, 6.0),
        "idle.py": FileFigures(20.0, 2.0),
        "edge.py": FileFigures(10.0, 1.5),  # 15%: not under
        "unmeasured.py": FileFigures(90.0),
    }
    # 500 s in all over 2 workers: the lane holds at most 0.8 * 250 = 200 s
    assert waiting_lane(figures, 2) == {"drive.py", "hz.py", "idle.py"}
    # over 4 workers, at most 100 s: drive.py would take the lane past it, the others fit
    assert waiting_lane(figures, 4) == {"hz.py", "idle.py"}
    assert waiting_lane(figures, 1) == set()  # one worker: no lane of its own


def test_the_files_that_wait_are_dealt_first_as_one_unit() -> None:
    seconds = {"walk.py": 200.0, "hub.py": 150.0, "b.py": 100.0, "drive.py": 90.0, "hz.py": 50.0}
    nodeids = ["hz.py::t", "b.py::t", "drive.py::t1", "hub.py::t", "walk.py::t", "drive.py::t2"]
    lane = {"drive.py", "hz.py"}
    assert _order(nodeids, seconds, late={"hub.py"}, workers=3, lane=lane) == [
        "drive.py::t1",
        "drive.py::t2",
        "hz.py::t",
        # the lane takes one worker's place in the first round: 2 for the others
        "walk.py::t",
        "b.py::t",
        "hub.py::t",
    ]
    # a file that waits for the build goes last in the lane
    assert _order(nodeids, seconds, late={"drive.py"}, workers=3, lane=lane)[:3] == [
        "hz.py::t",
        "drive.py::t1",
        "drive.py::t2",
    ]
    assert [scope_of(n, lane) for n in ("drive.py::t1", "hz.py::t", "b.py::t")] == [
        WAITING_LANE,
        WAITING_LANE,
        "b.py",
    ]


class _Worker:
    """What xdist's scheduler asks of a worker; it keeps the tests it was sent."""

    def __init__(self, name: str) -> None:
        self.gateway = SimpleNamespace(id=name)  # named in xdist's collection check
        self.sent: list[int] = []
        self.shutting_down = False

    def send_runtest_some(self, indices: list[int]) -> None:
        self.sent.extend(indices)

    def shutdown(self) -> None:
        self.shutting_down = True


def test_xdist_deals_the_lane_to_one_worker_as_one_unit(
    pytestconfig: pytest.Config, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The scheduler the suite's conftest gives xdist for `--dist loadfile`, driven through
    xdist's scheduling calls as its controller makes them (two workers)."""
    monkeypatch.setattr(pytestconfig.option, "tx", ["2*popen"])  # what xdist makes of `-n 2`
    collection = ["drive.py::a", "drive.py::b", "hz.py::a", "big.py::a", "big.py::b"]
    collection += ["big.py::c", "small.py::a"]
    scheduling = WaitingLaneScheduling(pytestconfig, lane={"drive.py", "hz.py"})
    workers = [_Worker("gw0"), _Worker("gw1")]
    for worker in workers:
        scheduling.add_node(worker)  # type: ignore[arg-type]
    for worker in workers:
        scheduling.add_node_collection(worker, collection)  # type: ignore[arg-type]
    scheduling.schedule()
    sent = [[collection[index] for index in worker.sent] for worker in workers]
    # the lane's three tests, two files, went to the first worker as one unit: more than two
    # tests pending, so xdist sent it nothing else yet; the other took the next file
    assert sent == [
        ["drive.py::a", "drive.py::b", "hz.py::a"],
        ["big.py::a", "big.py::b", "big.py::c"],
    ]


def test_the_table_has_a_lane_and_make_test_a_worker_for_it() -> None:
    """The measured table names files that wait, and the suite runs a worker beyond the
    others' for them (2 cores: 4 and 1)."""
    argv = pytest_argv([])
    workers = int(argv[argv.index("-n") + 1])
    lane = waiting_lane(read_figures(), workers)
    assert "tests/integration/lessons/test_skill_exercises.py" in lane
    assert workers == (os.cpu_count() or 1) + 3 if (os.cpu_count() or 1) >= 2 else workers == 0
