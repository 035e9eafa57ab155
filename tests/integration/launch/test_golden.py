"""`ros2 launch` output against the golden transcripts of real launch 3.4.3 / launch_ros 0.26.6."""

from __future__ import annotations

import os
import re
import sysconfig
import tempfile
from pathlib import Path

import pytest

GOLDEN = Path(__file__).resolve().parents[2] / "golden" / "launch"
pytestmark = [pytest.mark.ros, pytest.mark.slow]
_ROSOUT_RACE = b"Failed to publish log message to rosout: publisher's context is invalid"


def _golden(case: str) -> tuple[bytes, bytes, int]:
    text = (GOLDEN / f"{case}.txt").read_bytes()
    body = text.split(b"--- stdout ---\n", 1)[1]
    stdout, rest = body.split(b"--- stderr ---\n", 1)
    stderr, rest = rest.split(b"--- exit: ", 1)
    return stdout, stderr, int(rest.split(b" ")[0])


def _normalize(data: bytes, prefix: Path) -> list[bytes]:
    """Blank what varies run to run (see the golden README), collapse repeated lines."""
    site = sysconfig.get_paths()["purelib"].encode()
    data = data.replace(site, b"<venv>/lib/python3.11/site-packages")
    data = data.replace(str(prefix).encode(), b"install")
    data = data.replace(
        os.path.join(tempfile.gettempdir(), "launch_params_").encode(), b"<tmp>/launch_params_"
    )
    data = re.sub(rb"found below \S+", b"found below <log>", data)
    data = re.sub(rb"\[\d{10}\.\d{9}\]", b"[<time>]", data)
    data = re.sub(rb"pid \[?\d+\]?", b"pid <pid>", data)
    data = re.sub(rb"launch_params_\w+", b"launch_params_<x>", data)
    data = data.replace(sysconfig.get_paths()["purelib"].encode(), b"<venv>")
    lines: list[bytes] = []
    for line in data.split(b"\n"):
        # rclpy prints this when SIGINT lands during a log call of the node: a race of the
        # node's own shutdown (real launch shows it too, sometimes), not launch's output.
        if _ROSOUT_RACE in line:
            continue
        if not lines or line != lines[-1]:
            lines.append(line)
    return lines


def _traceback_span(lines: list[bytes]) -> tuple[int, int]:
    start = next(i for i, line in enumerate(lines) if b"Traceback (most recent" in line)
    end = next(i for i, line in enumerate(lines) if line.startswith(b"[param_vel-1] Keyboard"))
    return start, end


@pytest.mark.parametrize(
    "case,file",
    [
        ("launch_py", "param_vel.launch.py"),
        ("launch_yaml", "param_vel.launch.yaml"),
        ("launch_py_params_file", "param_vel_file.launch.py"),
    ],
)
def test_launch_output_matches_golden(
    raw_launch, fixture_prefix: Path, case: str, file: str
) -> None:
    run = raw_launch("parameter_tests", file)
    assert run.wait_for(b"Velocity parameter is", count=3), run.stdout
    run.interrupt_group()
    code = run.finish()
    stdout, stderr, exit_code = _golden(case)
    ours, real = _normalize(run.stdout, fixture_prefix), _normalize(stdout, fixture_prefix)
    # The node's KeyboardInterrupt traceback depends on where in rclpy the SIGINT lands (in
    # a timer callback it comes chained, its first frame in rclpy/task.py): compare all of
    # launch's output up to it and from its last line exactly; between, only node lines.
    start, end = _traceback_span(real)
    ours_start, ours_end = _traceback_span(ours)
    assert ours[: start + 1] == real[: start + 1]
    assert ours_start == start
    assert all(line.startswith(b"[param_vel-1] ") for line in ours[start:ours_end])
    assert ours[ours_end:] == real[end:]
    assert run.stderr == stderr
    assert code == exit_code
    pid = int(re.search(rb"process started with pid \[(\d+)\]", run.stdout).group(1))
    assert not Path(f"/proc/{pid}").exists()


def test_missing_package_matches_golden(raw_launch, fixture_prefix: Path) -> None:
    run = raw_launch("no_such_pkg", "param_vel.launch.py")
    code = run.finish()
    _, stderr, exit_code = _golden("launch_missing_package")
    expected = stderr.replace(b"'install'", repr(str(fixture_prefix)).encode())
    expected = expected.replace(b"'<venv>'", repr(os.sys.prefix).encode())
    assert (run.stdout, run.stderr, code) == (b"", expected, exit_code)
