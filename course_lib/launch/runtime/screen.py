"""What launch prints: `[LEVEL] [logger]: message` on stdout, and the launch log folder."""

from __future__ import annotations

import contextlib
import datetime
import os
import socket
import sys
import time
from pathlib import Path
from typing import TextIO

__all__ = ["LaunchLog", "log_directory"]


def log_directory(env: dict[str, str] | None = None) -> Path:
    """Return the ROS log folder: $ROS_LOG_DIR, else $ROS_HOME/log, else ~/.ros/log."""
    env = dict(os.environ) if env is None else env
    base = env.get("ROS_LOG_DIR") or os.path.join(env.get("ROS_HOME") or "~/.ros", "log")
    return Path(os.path.normpath(os.path.expanduser(base)))


def _make_run_dir(base: Path) -> Path:
    while True:
        stamp = datetime.datetime.now().strftime("%Y-%m-%d-%H-%M-%S-%f")
        path = base / f"{stamp}-{socket.gethostname()}-{os.getpid()}"
        if not path.is_dir():
            path.mkdir(parents=True, exist_ok=True)
            break
    latest = base / "latest"
    with contextlib.suppress(OSError):
        if latest.is_symlink():
            latest.unlink()
        if not latest.exists():
            latest.symlink_to(path, target_is_directory=True)
    return path


class LaunchLog:
    """The screen (stdout) and the launch.log file of one launch run."""

    def __init__(self, stream: TextIO | None = None, *, log_dir: Path | None = None) -> None:
        self.stream = stream or sys.stdout
        self.run_dir = _make_run_dir(log_dir or log_directory())
        self._file = open(self.run_dir / "launch.log", "a", encoding="utf-8")  # noqa: SIM115
        self._own: dict[str, TextIO] = {}

    def screen(self, text: str) -> None:
        """Print one line on the screen as launch's handler does (text + newline, flushed)."""
        try:
            self.stream.write(text + "\n")
            self.stream.flush()
        except (BrokenPipeError, ValueError):
            pass

    def file(self, text: str, name: str | None = None) -> None:
        """Append a line to launch.log (or to `<name>` in the run folder)."""
        handle: TextIO = self._file
        if name is not None:
            if name not in self._own:
                self._own[name] = open(self.run_dir / name, "a", encoding="utf-8")  # noqa: SIM115
            handle = self._own[name]
        handle.write(text + "\n")
        handle.flush()

    def log(self, logger: str, level: str, message: str) -> None:
        """Log a launch message: screen `[LEVEL] [logger]: msg`, file with a timestamp."""
        self.screen(f"[{level}] [{logger}]: {message}")
        self.file(f"{time.time():.7f} [{level}] [{logger}]: {message}")

    def close(self) -> None:
        """Close the log files."""
        for handle in (self._file, *self._own.values()):
            handle.close()
