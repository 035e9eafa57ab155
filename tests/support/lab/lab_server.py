"""JupyterLab for browser tests, started as `make lab` starts it: headless, free port, token."""

from __future__ import annotations

import re
import secrets
import sys
import time
import urllib.error
import urllib.request
from collections.abc import Sequence
from pathlib import Path

import nbformat
from suite_env import independent_env

from course_lib.core.paths import NOTEBOOKS_DIR, REPO_ROOT
from course_lib.processes.children import ChildProcess, spawn

__all__ = ["ARTIFACTS", "LabServer"]

ARTIFACTS = REPO_ROOT / "test-artifacts" / "browser"
_OPENER = urllib.request.build_opener(urllib.request.ProxyHandler({}))  # the lab is local


class LabServer:
    """`python -m course_lib lab` on copies of lessons (running them never rewrites notebooks/)."""

    def __init__(
        self,
        lessons: list[str],
        folder: Path,
        timeout: float = 60.0,
        env: dict[str, str] | None = None,
        extra: Sequence[str] = (),
    ) -> None:

        self.folder = folder
        folder.mkdir(parents=True, exist_ok=True)
        for name in lessons:  # without stored outputs: only this run's outputs are checked
            notebook = nbformat.read(NOTEBOOKS_DIR / name, as_version=4)
            for cell in notebook.cells:
                if cell.cell_type == "code":
                    cell.outputs, cell.execution_count = [], None
            nbformat.write(notebook, folder / name)
        self.token = secrets.token_hex(16)
        env = env or independent_env()
        argv = [
            sys.executable, "-m", "course_lib", "lab",
            "--no-browser", "--ServerApp.port=0", f"--IdentityProvider.token={self.token}",
            "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate",
            # the test's own settings: never the learner's (~/.jupyter/lab/user-settings)
            f"--LabApp.user_settings_dir={folder / '.jupyterlab-settings'}",
            *extra,
        ]  # fmt: skip
        self.process: ChildProcess = spawn(
            argv, name="lab", env=env, cwd=REPO_ROOT, merge_stderr=True
        )
        line = self.process.wait_for_line(r"http://127\.0\.0\.1:\d+/lab", timeout)
        if line is None:
            self.stop()
            raise RuntimeError(f"JupyterLab did not start:\n{self.text()}")
        self.port = int(re.search(r"127\.0\.0\.1:(\d+)/", line.text)[1])  # type: ignore[index]
        domain = re.search(r"ROS_DOMAIN_ID=(\d+)", self.process.text())
        self.domain_id = int(domain[1]) if domain else None
        self._wait_until_serving(timeout)

    def answers(self) -> bool:
        """Return whether a server answers this lab's API at its address with its token."""
        request = urllib.request.Request(
            f"{self.base_url}/api/status", headers={"Authorization": f"token {self.token}"}
        )
        try:
            with _OPENER.open(request, timeout=5) as reply:
                reply.read()
            return True
        except (urllib.error.URLError, OSError):
            return False

    def _wait_until_serving(self, timeout: float) -> None:
        """Return once JupyterLab answers its API with this token; raise if it never does.

        Jupyter Server prints its address before it listens (it binds the port when its event
        loop starts): a request sent as soon as the address shows can be refused.
        """
        request = urllib.request.Request(
            f"{self.base_url}/api/status", headers={"Authorization": f"token {self.token}"}
        )
        deadline = time.monotonic() + timeout
        while True:
            try:
                with _OPENER.open(request, timeout=10) as reply:
                    reply.read()
                return
            except urllib.error.HTTPError as exc:  # another server took the port
                problem = f"{self.base_url} answers {exc.code} to this lab's token"
            except (urllib.error.URLError, OSError) as exc:
                problem = f"{self.base_url} does not answer ({exc})"
                if self.process.alive and time.monotonic() < deadline:
                    time.sleep(0.02)
                    continue
            self.stop()
            raise RuntimeError(f"JupyterLab printed its address but {problem}:\n{self.text()}")

    def text(self) -> str:
        """Return the end of what the lab printed (for failure messages)."""
        return self.process.text()[-3000:]

    @property
    def base_url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def lab_url(self, notebook: str) -> str:
        """Return the address that opens `notebook` (a copied lesson) in a fresh workspace."""
        path = (self.folder / notebook).relative_to(REPO_ROOT)
        return f"{self.base_url}/lab/tree/{path}?reset&token={self.token}"

    def stop(self) -> None:
        """Stop JupyterLab like Ctrl-C (its kernels, terminals and their children go too); keep
        what it printed in its folder (lab.log: what a failed test's reader looks at first)."""
        self.process.stop(timeout=15.0)
        (self.folder / "lab.log").write_text(self.process.text(), encoding="utf-8")
