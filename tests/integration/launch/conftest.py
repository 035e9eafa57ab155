"""Fixtures of the launch integration tests: a session, the fixture prefix, raw launches."""

from __future__ import annotations

import importlib.util
import os
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from course_lib.session.session import Session

_PREFIX_PY = Path(__file__).resolve().parents[2] / "fixtures" / "launch_pkg" / "prefix.py"


def _prefix_module():  # type: ignore[no-untyped-def]
    spec = importlib.util.spec_from_file_location("launch_fixture_prefix", _PREFIX_PY)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def launch_session() -> Iterator[Session]:
    """Yield a course session (own domain) for one test module."""
    session = Session()
    try:
        yield session
    finally:
        session.close()


@pytest.fixture(scope="module")
def fixture_prefix(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Return an ament prefix holding the fixture package `parameter_tests`."""
    return _prefix_module().make_prefix(tmp_path_factory.mktemp("launch_prefix"))


@pytest.fixture(scope="module")
def launch_env(
    launch_session: Session, fixture_prefix: Path, tmp_path_factory: pytest.TempPathFactory
) -> dict[str, str]:
    """Return the session's environment with only the fixture package indexed."""
    env = _prefix_module().prefix_env(fixture_prefix, launch_session.env)
    env["ROS_LOG_DIR"] = str(tmp_path_factory.mktemp("ros_log"))
    env.pop("RCUTILS_COLORIZED_OUTPUT", None)
    return env


class RawLaunch:
    """`python -m course_lib.launch ...` in its own process group, bytes kept exactly."""

    def __init__(
        self, argv: list[str], env: dict[str, str], *, command: list[str] | None = None
    ) -> None:
        self.proc = subprocess.Popen(
            [*(command or [sys.executable, "-m", "course_lib.launch"]), *argv],
            env=env,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            start_new_session=True,
        )
        self.stdout = b""
        self.stderr = b""
        self._cond = threading.Condition()
        self._threads = [
            threading.Thread(target=self._read, args=(s,), daemon=True)
            for s in ("stdout", "stderr")
        ]
        for thread in self._threads:
            thread.start()

    def _read(self, stream: str) -> None:
        pipe = getattr(self.proc, stream)
        for chunk in iter(lambda: pipe.read1(65536), b""):
            with self._cond:
                setattr(self, stream, getattr(self, stream) + chunk)
                self._cond.notify_all()
        pipe.close()

    def wait_for(self, data: bytes, count: int = 1, timeout: float = 20.0) -> bool:
        """Wait until stdout holds `data` `count` times."""
        deadline = time.monotonic() + timeout
        with self._cond:
            while self.stdout.count(data) < count:
                left = deadline - time.monotonic()
                if left <= 0 or self.proc.poll() is not None:
                    return self.stdout.count(data) >= count
                self._cond.wait(min(left, 0.1))
        return True

    def interrupt_group(self) -> None:
        """Ctrl-C in a terminal: SIGINT to the whole process group."""
        os.killpg(self.proc.pid, signal.SIGINT)

    def finish(self, timeout: float = 20.0) -> int:
        """Wait for the exit and the end of the output; return the exit code."""
        code = self.proc.wait(timeout)
        for thread in self._threads:
            thread.join(5.0)
        return code

    def kill(self) -> None:
        """Kill the whole group (clean-up after a failed test)."""
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGKILL)
            self.proc.wait(5.0)
        for thread in self._threads:
            thread.join(5.0)


@pytest.fixture
def raw_launch(launch_env: dict[str, str]) -> Iterator:
    """Start raw launches; kill what is left at the end of the test."""
    started: list[RawLaunch] = []

    def start(*argv: str) -> RawLaunch:
        run = RawLaunch(list(argv), launch_env)
        started.append(run)
        return run

    yield start
    for run in started:
        run.kill()


ROS2 = Path(sys.executable).parent / "ros2"  # the course's console command, as in a terminal


@pytest.fixture
def ros2_launch(launch_env: dict[str, str]) -> Iterator:
    """Start `ros2 launch ...` (the console command); kill what is left at the end."""
    env = dict(launch_env)
    env["PATH"] = os.pathsep.join([str(ROS2.parent), env.get("PATH", "")])
    env["USER"] = "learner"
    started: list[RawLaunch] = []

    def start(*argv: str) -> RawLaunch:
        run = RawLaunch(list(argv), env, command=[str(ROS2), "launch"])
        started.append(run)
        return run

    yield start
    for run in started:
        run.kill()
