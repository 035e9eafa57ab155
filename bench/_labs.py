"""Shared by the benches that start real labs: a lab as `make lab` starts it, its kernels.

Not a bench script itself (the leading underscore keeps `python -m bench` from running it).
Every process started here is owned (course_lib.processes.children): a lab dies with the
bench, and a kernel carries its lab's owner tag as one JupyterLab starts would, so a later
session reaps it if the bench was killed before it could shut the kernel down.
"""

from __future__ import annotations

import os
import queue
import re
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import psutil
from jupyter_client.manager import KernelManager
from suite_env import independent_env

from course_lib.core.host.procfs import pid_namespace
from course_lib.core.host.scheduling import CLASS_HOST_ENV
from course_lib.core.paths import REPO_ROOT, runtime_dir
from course_lib.lab.protocol import SOCKET_ENV
from course_lib.processes.children import ChildProcess, spawn
from course_lib.processes.orphans import OWNER_ENV, OWNER_NS_ENV, owner_tag

__all__ = ["CellKernel", "Lab", "LabKernel", "collect_cell", "start_lab", "tree_pids"]

_URL = re.compile(r"(http://127\.0\.0\.1:(\d+)/lab\S*)")


@dataclass
class Lab:
    """A running lab: its process, the environment its kernels get, its JupyterLab address."""

    process: ChildProcess
    env: dict[str, str]
    port: int
    token: str

    @property
    def pid(self) -> int:
        return self.process.pid

    def stop(self) -> None:
        """Stop the lab (JupyterLab, daemon, world, view and nodes go with it)."""
        self.process.stop(timeout=15.0)


def start_lab(timeout: float = 90.0, *, class_host: bool = False) -> Lab:
    """Start `python -m course_lib lab` headless on a free port; return it once it serves
    (`class_host`: as on a class's host, where the hub sets CLASS_HOST_ENV)."""
    argv = [sys.executable, "-m", "course_lib", "lab", "--no-browser", "--ServerApp.port=0"]
    env = independent_env(**({CLASS_HOST_ENV: "1"} if class_host else {}))
    lab = spawn(argv, name="jupyterlab", env=env, cwd=REPO_ROOT, merge_stderr=True)
    if lab.wait_for_line(_URL.pattern, timeout) is None:
        text = lab.text()[-2000:]
        lab.stop(timeout=15.0)
        raise SystemExit(f"the lab did not start within {timeout:g} s:\n{text}")
    text = lab.text()
    url = _URL.search(text)
    domain = re.search(r"ROS_DOMAIN_ID=(\d+)", text)
    if url is None or domain is None:
        lab.stop(timeout=15.0)
        raise SystemExit(f"the lab printed no address or domain:\n{text[-2000:]}")
    token = re.search(r"token=(\w+)", url[1])
    socket = runtime_dir() / f"lab-{lab.pid}.sock"
    env = independent_env(
        ROS_DOMAIN_ID=domain[1],
        COURSE_LAB="1",
        **{SOCKET_ENV: str(socket), OWNER_ENV: owner_tag(lab.pid), OWNER_NS_ENV: pid_namespace()},
    )
    return Lab(lab, env, int(url[2]), token[1] if token else "")


class CellKernel:
    """What the benches do with a kernel: `submit(code)`, then `collect(msg_id)`; `run(code)`.
    A subclass submits and reads the kernel's messages (`read_message`)."""

    def submit(self, code: str) -> str:
        raise NotImplementedError

    def read_message(self, timeout: float) -> dict[str, Any]:
        """Return the kernel's next message; queue.Empty or TimeoutError when none came."""
        raise NotImplementedError

    def collect(self, msg_id: str, timeout: float = 120.0) -> str:
        """Wait for the cell `msg_id` to finish; return what it printed, raise if it failed."""
        return collect_cell(self.read_message, msg_id, timeout)

    def run(self, code: str, timeout: float = 120.0) -> float:
        """Execute `code` as one cell; return its wall time in seconds, raise if it failed."""
        started = time.monotonic()
        self.collect(self.submit(code), timeout)
        return time.monotonic() - started


class LabKernel(CellKernel):
    """A real ipykernel with a lab's environment, as that lab's JupyterLab gives its kernels."""

    def __init__(self, lab: Lab) -> None:
        self.manager = KernelManager(kernel_name="python3")
        self.manager.start_kernel(env=lab.env, cwd=str(REPO_ROOT))
        self.client: Any = self.manager.blocking_client()
        self.client.start_channels()
        self.client.wait_for_ready(timeout=60)

    @property
    def pid(self) -> int:
        return self.manager.provisioner.pid  # type: ignore[union-attr]

    def submit(self, code: str) -> str:
        """Start executing `code` as one cell; return its message id for collect()."""
        return self.client.execute(code, store_history=False)

    def read_message(self, timeout: float) -> dict[str, Any]:
        return dict(self.client.get_iopub_msg(timeout=timeout))

    def shutdown(self) -> None:
        """Stop the kernel (and every course process it owns)."""
        try:
            self.client.stop_channels()
        finally:
            self.manager.shutdown_kernel(now=True)


def collect_cell(read: Callable[[float], dict[str, Any]], msg_id: str, timeout: float) -> str:
    """Read a kernel's messages with `read(seconds)` (queue.Empty or TimeoutError when none
    came) until the cell `msg_id` is done; return what it printed, raise if it failed."""
    printed: list[str] = []
    deadline = time.monotonic() + timeout
    while True:
        remaining = deadline - time.monotonic()
        if remaining <= 0:
            raise TimeoutError(f"a cell did not finish within {timeout:g} s")
        try:
            msg = read(remaining)
        except (queue.Empty, TimeoutError):  # the deadline is checked above
            continue
        if msg["parent_header"].get("msg_id") != msg_id:
            continue
        kind, content = msg["msg_type"], msg["content"]
        if kind == "stream":
            printed.append(content["text"])
        elif kind == "error":
            raise RuntimeError(
                f"cell failed: {content['ename']}: {content['evalue']}\n{''.join(printed)}"
            )
        elif kind == "status" and content["execution_state"] == "idle":
            return "".join(printed)


def tree_pids(roots: list[int]) -> list[int]:
    """Return `roots` and all their live descendants."""
    found: list[int] = []
    for pid in roots:
        try:
            root = psutil.Process(pid)
            found += [root.pid, *(p.pid for p in root.children(recursive=True))]
        except psutil.NoSuchProcess:
            continue
    return sorted(set(found) - {os.getpid()})
