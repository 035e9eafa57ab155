"""JupyterLab for browser tests, started as `make lab` starts it: headless, free port, token."""

from __future__ import annotations

import re
import secrets
import sys
from pathlib import Path

import nbformat

from course_lib.paths import NOTEBOOKS_DIR, REPO_ROOT
from course_lib.processes import ChildProcess, spawn
from course_lib.testing import independent_env

__all__ = ["ARTIFACTS", "LabServer"]

ARTIFACTS = REPO_ROOT / "test-artifacts" / "browser"


class LabServer:
    """`python -m course_lib lab` on copies of lessons (running them never rewrites notebooks/)."""

    def __init__(
        self,
        lessons: list[str],
        folder: Path,
        timeout: float = 60.0,
        env: dict[str, str] | None = None,
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
        ]  # fmt: skip
        self.process: ChildProcess = spawn(
            argv, name="lab", env=env, cwd=REPO_ROOT, merge_stderr=True
        )
        line = self.process.wait_for_line(r"http://127\.0\.0\.1:\d+/lab", timeout)
        if line is None:
            self.stop()
            raise RuntimeError(f"JupyterLab did not start:\n{self.process.text()[-3000:]}")
        self.port = int(re.search(r"127\.0\.0\.1:(\d+)/", line.text)[1])  # type: ignore[index]
        domain = re.search(r"ROS_DOMAIN_ID=(\d+)", self.process.text())
        self.domain_id = int(domain[1]) if domain else None

    @property
    def base_url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def lab_url(self, notebook: str) -> str:
        """Return the address that opens `notebook` (a copied lesson) in a fresh workspace."""
        path = (self.folder / notebook).relative_to(REPO_ROOT)
        return f"{self.base_url}/lab/tree/{path}?reset&token={self.token}"

    def stop(self) -> None:
        """Stop JupyterLab like Ctrl-C (its kernels, terminals and their children go too)."""
        self.process.stop(timeout=15.0)
