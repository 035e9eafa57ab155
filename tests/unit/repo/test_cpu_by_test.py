"""The suite's CPU by test (tests/harness/cpu_by_test.py): what it counts and how it sums."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from cpu_by_test import CpuMeter, read_records, record, summary

SUPPORT = Path(__file__).resolve().parents[2] / "harness"

# A meter in one kind of cgroup (the script's argument: its usage file), or "skip" if none
_METER_OF_ONE_KIND = """
import sys
import cpu_by_test
kind = [pair for pair in cpu_by_test._own_cgroups() if pair[1] == sys.argv[1]]
cpu_by_test._own_cgroups = lambda: kind
meter = cpu_by_test.CpuMeter()
if meter.folder is None:
    print("skip", meter.problem); sys.exit(0)
"""
EACH_KIND = pytest.mark.parametrize(
    "usage", ["cpuacct.usage", "cpu.stat"], ids=["cgroup-v1", "cgroup-v2"]
)


def _figures(script: str, usage: str) -> tuple[dict[str, str], str]:
    """Run `script` after a meter of the `usage` kind is made; return the figures it printed
    (name and value per line) and its output; skip where this host has no such cgroup."""
    out = subprocess.run(
        [sys.executable, "-c", _METER_OF_ONE_KIND + script, usage],
        env={"PYTHONPATH": str(SUPPORT), "PATH": "/usr/bin:/bin"},
        capture_output=True,
        text=True,
        timeout=60,
        check=True,
    ).stdout
    if out.startswith("skip"):
        pytest.skip(f"no cgroup to measure in: {out}")
    return dict(line.split() for line in out.splitlines()), out


# A process whose child burns 0.5 s of CPU after its parent has gone (re-parented, as a lab's
# simulation or a browser's renderer can be): getrusage never counts it, the cgroup does.
_ORPHAN_BURNS = """
import os, resource, sys, time
before, children = meter.seconds(), resource.getrusage(resource.RUSAGE_CHILDREN)
read, write = os.pipe()
if os.fork() == 0:
    if os.fork() == 0:
        os.close(read)
        end = time.process_time() + 0.5
        while time.process_time() < end:
            pass
        os._exit(0)  # its end closes the pipe's last writer
    os._exit(0)
os.close(write)
os.wait()
os.read(read, 1)  # returns once the grandchild has exited
time.sleep(0.05)
after = resource.getrusage(resource.RUSAGE_CHILDREN)
print("cgroup", meter.seconds() - before)
print("rusage", after.ru_utime + after.ru_stime - children.ru_utime - children.ru_stime)
meter.close()
"""


@EACH_KIND
def test_a_re_parented_childs_cpu_is_counted(usage: str) -> None:
    figures, out = _figures(_ORPHAN_BURNS, usage)
    assert float(figures["cgroup"]) >= 0.45, out
    assert float(figures["rusage"]) < 0.1, out  # what getrusage would have said


# A child that burns 0.5 s of CPU once told to, counted apart from the tests: the test process's
# own figure leaves it out, the named one holds it with the wall time until it ended, and
# closing removes its cgroup.
_APART_BURNS = """
import subprocess, sys, time
burn = "import sys, time\\nsys.stdin.readline()\\nend = time.process_time() + 0.5\\n"
burn += "while time.process_time() < end:\\n    pass"
before = meter.seconds()
child = subprocess.Popen([sys.executable, "-c", burn], stdin=subprocess.PIPE)
meter.count_apart(child.pid, "tests/browser/class_hub.py::a build", watch_period_s=0.1)
since = time.monotonic()
child.communicate(b"go\\n")
time.sleep(1.0)  # the meter looks every 0.1 s here
print("tests", meter.seconds() - before)
(name, cpu, wall), = meter.apart()
print("apart", cpu if name.endswith("a build") else -1)
print("after_end", time.monotonic() - since - wall)  # its wall time stops at its end
folder = meter.folder.parent / f"course-tests-{child.pid}"
meter.close()
print("left", int(folder.exists()))
"""


@EACH_KIND
def test_a_process_counted_apart_is_no_tests(usage: str) -> None:
    figures, out = _figures(_APART_BURNS, usage)
    assert float(figures["apart"]) >= 0.45, out
    assert float(figures["tests"]) < 0.2, out  # without count_apart: the burn's 0.5 s
    assert float(figures["after_end"]) >= 0.5, out  # without the end noticed: about 0
    assert figures["left"] == "0", out


# A cgroup counted apart that another run's clean-up removed once empty: left out of the
# figures, not an error at the end of the run.
_APART_GONE = """
import subprocess
child = subprocess.Popen([sys.executable, "-c", "pass"])
meter.count_apart(child.pid, "tests/browser/class_hub.py::a build", watch_period_s=0.1)
child.wait()
(meter.folder.parent / f"course-tests-{child.pid}").rmdir()
print("figures", len(meter.apart()))
meter.close()
"""


@EACH_KIND
def test_a_cgroup_counted_apart_that_is_gone_is_left_out(usage: str) -> None:
    figures, out = _figures(_APART_GONE, usage)
    assert figures["figures"] == "0", out


def test_the_summary_ranks_files_and_shares_folders(tmp_path: Path) -> None:
    record(tmp_path, "tests/browser/test_walk.py::test_a", 30.0, 60.0)
    record(tmp_path, "tests/unit/core/test_x.py::test_b", 1.0, 2.0)
    record(tmp_path, "tests/browser/test_walk.py::test_c", 9.0, 20.0)
    record(tmp_path, "notebooks/01_setup_check.ipynb::Cell 0", 10.0, 5.0)
    (tmp_path / "torn.jsonl").write_text('{"test": "tests/x.py::t", "cpu_s": 1')

    lines = summary(read_records(tmp_path), top=2)

    assert lines == [
        "   CPU-s   wall-s  file",
        "    39.0     80.0  tests/browser/test_walk.py",
        "    10.0      5.0  notebooks/01_setup_check.ipynb",
        "    50.0 CPU-s in all (3 files): tests/browser 78%, notebooks 20%, tests/unit 2%",
    ]


def test_no_figures_make_no_table() -> None:
    assert summary([]) == []


def test_a_meter_that_cannot_measure_reads_zero_and_says_why(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    import cpu_by_test

    monkeypatch.setattr(cpu_by_test, "_own_cgroups", lambda: [])
    meter = CpuMeter()
    assert (meter.folder, meter.seconds()) == (None, 0.0)
    assert meter.problem == "no cgroup filesystem here"


def test_leftovers_of_earlier_runs_go_innermost_first_and_busy_ones_stay(tmp_path: Path) -> None:
    import cpu_by_test

    (tmp_path / "course-tests-1" / "course-tests-2").mkdir(parents=True)  # a run's, empty
    (tmp_path / "course-tests-3" / "course-tests-4").mkdir(parents=True)
    (tmp_path / "course-tests-3" / "course-tests-4" / "busy").touch()  # a process still in it
    (tmp_path / "someone-elses").mkdir()

    cpu_by_test._remove_empty_leftovers(tmp_path)

    left = sorted(str(p.relative_to(tmp_path)) for p in tmp_path.rglob("*"))
    assert left == [
        "course-tests-3",
        "course-tests-3/course-tests-4",
        "course-tests-3/course-tests-4/busy",
        "someone-elses",
    ]
