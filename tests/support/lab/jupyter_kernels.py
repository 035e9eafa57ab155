"""Drive real Jupyter kernels from tests: start one as JupyterLab would, run code, read outputs."""

from __future__ import annotations

import queue
import re
import tempfile
import time
from contextlib import suppress
from dataclasses import dataclass, field
from pathlib import Path

import psutil
from jupyter_client.manager import KernelManager
from suite_env import independent_env

from course_lib.core.host.procfs import environ as process_environ
from course_lib.core.host.procfs import pid_alive
from course_lib.core.paths import REPO_ROOT
from course_lib.core.waiting import wait_until
from course_lib.processes.orphans import OWNER_ENV

__all__ = [
    "CellResult",
    "Kernel",
    "course_pids",
    "describe",
    "pid_alive",
    "process_tree",
    "wait_gone",
]

_ANSI = re.compile(r"\x1b\[[0-9;]*m")


@dataclass
class CellResult:
    """What one execution printed: text streams, rich outputs' plain text, and the error."""

    text: str = ""
    html: str = ""
    error: str = ""
    outputs: list[dict] = field(default_factory=list)

    @property
    def everything(self) -> str:
        """Return all text (streams, results, error) in one string, without colour codes."""
        return _ANSI.sub("", f"{self.text}\n{self.error}")


class Kernel:
    """A real ipykernel started with jupyter_client, in the repository folder."""

    def __init__(self, env: dict[str, str] | None = None) -> None:
        # its own stderr (not the worker's, which no report shows): said if it dies starting
        self._stderr = tempfile.TemporaryFile()  # noqa: SIM115 (closed by shutdown)
        # Unix sockets in a folder of its own: TCP ports are chosen free, released, and bound by
        # the kernel moments later, and on a busy host another process took one in between
        # (ci88: "Address already in use" as the kernel started).
        self._sockets = tempfile.TemporaryDirectory(prefix="kernel-")
        sockets = Path(self._sockets.name)
        self.manager = KernelManager(
            kernel_name="python3",
            transport="ipc",
            ip=str(sockets / "channel"),
            connection_file=str(sockets / "connection.json"),
        )
        self.manager.start_kernel(
            env=env or independent_env(), cwd=str(REPO_ROOT), stderr=self._stderr
        )
        self.client = self.manager.blocking_client()
        self.client.start_channels()
        try:
            self.client.wait_for_ready(timeout=60)
        except RuntimeError as error:  # ci59: "Kernel died before replying to kernel_info"
            said = self.stderr_tail()
            self.shutdown()
            raise RuntimeError(f"{error}; its stderr ended:\n{said}") from error

    def stderr_tail(self, size: int = 4000) -> str:
        """Return the end of what the kernel process wrote to its stderr."""
        self._stderr.seek(0, 2)
        self._stderr.seek(max(0, self._stderr.tell() - size))
        return self._stderr.read().decode("utf-8", "replace")

    @property
    def pid(self) -> int:
        """Return the kernel's process id."""
        return self.manager.provisioner.pid  # type: ignore[union-attr]

    def submit(self, code: str) -> str:
        """Start executing `code` as one cell; return the message id for collect()."""
        return self.client.execute(code, store_history=False)

    def run(self, code: str, timeout: float = 60.0) -> CellResult:
        """Execute `code` as one cell and collect its outputs until the kernel is idle."""
        return self.collect(self.submit(code), timeout, code)

    def collect(self, msg_id: str, timeout: float = 60.0, code: str = "") -> CellResult:
        """Collect the outputs of a submitted cell until the kernel is idle again."""
        result = CellResult()
        deadline = time.monotonic() + timeout
        while True:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise TimeoutError(f"cell did not finish within {timeout:g} s:\n{code}")
            try:
                msg = self.client.get_iopub_msg(timeout=remaining)
            except queue.Empty:
                continue
            if msg["parent_header"].get("msg_id") != msg_id:
                continue
            kind, content = msg["msg_type"], msg["content"]
            if kind == "status" and content["execution_state"] == "idle":
                return result
            if kind == "stream":
                result.text += content["text"]
            elif kind in ("execute_result", "display_data"):
                result.outputs.append(content["data"])
                result.text += content["data"].get("text/plain", "") + "\n"
                result.html += content["data"].get("text/html", "")
            elif kind == "error":
                result.error = f"{content['ename']}: {content['evalue']}\n" + "\n".join(
                    content["traceback"]
                )

    def ok(self, code: str, timeout: float = 60.0) -> CellResult:
        """Run `code` and fail with its traceback if it raised."""
        result = self.run(code, timeout)
        assert not result.error, result.everything
        return result

    def shutdown(self) -> None:
        """Stop the kernel (and with it every course process it owns)."""
        with suppress(Exception):
            self.client.stop_channels()
        with suppress(Exception):
            self.manager.shutdown_kernel(now=True)
        with suppress(Exception):
            self.manager.cleanup_resources()
        self._stderr.close()
        self._sockets.cleanup()


def course_pids(owner_pid: int) -> list[int]:
    """Return the live course processes that `owner_pid` started (tagged COURSE_OWNER)."""
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            tag = process_environ(int(entry.name)).get(OWNER_ENV, "")
            if tag.partition(":")[0] == str(owner_pid) and pid_alive(int(entry.name)):
                found.append(int(entry.name))
    return found


def wait_gone(pids: list[int], timeout: float) -> list[int]:
    """Wait until none of `pids` runs; return those still running at the timeout."""
    wait_until(lambda: not any(pid_alive(pid) for pid in pids), timeout)  # /proc: no event
    return [pid for pid in pids if pid_alive(pid)]


def process_tree(pid: int) -> list[int]:
    """Return `pid`'s descendants and the course processes it owns."""
    try:
        tree = [p.pid for p in psutil.Process(pid).children(recursive=True)]
    except psutil.NoSuchProcess:
        tree = []
    return sorted(set(tree) | set(course_pids(pid)))


def describe(pids: list[int]) -> str:
    """Return `ps`-like lines for `pids`, for failure messages."""
    lines = []
    for pid in pids:
        try:
            lines.append(f"{pid} {' '.join(psutil.Process(pid).cmdline())[:120]}")
        except psutil.NoSuchProcess:
            continue
    return "\n".join(lines)
