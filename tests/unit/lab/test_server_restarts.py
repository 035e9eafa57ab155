"""Which ended Jupyter servers a lab starts again, and at what address (`ServerRestarts`)."""

from __future__ import annotations

import json
import signal
from pathlib import Path

import pytest

from course_lib.lab.server_restarts import RESTARTS_MAX, ServerRestarts, runtime_file

PID = 4321


@pytest.fixture
def restarts(tmp_path: Path) -> ServerRestarts:
    env = {"JUPYTER_RUNTIME_DIR": str(tmp_path)}
    runtime_file(env, PID).write_text(
        json.dumps({"port": 8891, "token": "abc", "url": "http://127.0.0.1:8891/"})
    )
    (tmp_path / f"jpserver-{PID}-open.html").write_text("")
    return ServerRestarts(env)


def test_a_killed_server_starts_again_at_its_port_with_its_token(
    restarts: ServerRestarts, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    again = restarts.argv_again(PID, -signal.SIGKILL)
    assert again is not None
    assert "--ServerApp.port=8891" in again and "--ServerApp.port_retries=0" in again
    assert "--IdentityProvider.token=abc" in again
    assert "--ServerApp.open_browser=False" in again
    assert list(tmp_path.iterdir()) == [], "the killed server's runtime files are left"
    said = capsys.readouterr().err
    assert "killed (signal 9)" in said and "http://127.0.0.1:8891/" in said and "Save" in said


@pytest.mark.parametrize("code", [0, 1, -signal.SIGINT, -signal.SIGTERM, -signal.SIGHUP, None])
def test_a_server_that_ended_or_was_asked_to_stop_stays_stopped(
    restarts: ServerRestarts, code: int | None
) -> None:
    assert restarts.argv_again(PID, code) is None


def test_a_server_killed_again_and_again_stays_stopped(
    restarts: ServerRestarts, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    env = {"JUPYTER_RUNTIME_DIR": str(tmp_path)}
    for pid in range(RESTARTS_MAX + 1):
        runtime_file(env, pid).write_text(json.dumps({"port": 8891, "token": "abc"}))
    assert all(restarts.argv_again(pid, -9) for pid in range(RESTARTS_MAX))
    assert restarts.argv_again(RESTARTS_MAX, -9) is None
    assert "not again" in capsys.readouterr().err


def test_a_server_with_no_runtime_file_stays_stopped(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    restarts = ServerRestarts({"JUPYTER_RUNTIME_DIR": str(tmp_path)})
    assert restarts.argv_again(PID, -9) is None
    assert "run `make lab` again" in capsys.readouterr().err


def test_the_restart_s_options_replace_the_first_server_s() -> None:
    from course_lib.lab.server_restarts import argv_with

    argv = ["jupyter", "lab", "--no-browser", "--ServerApp.port=0", "--IdentityProvider.token=a"]
    again = [
        "--ServerApp.port=8891",
        "--IdentityProvider.token=a",
        "--ServerApp.open_browser=False",
    ]
    assert argv_with(argv, again) == ["jupyter", "lab", *again]
