"""`python -m course_lib image [COMMAND ...]`: the entry point of the course's image (Dockerfile).

One image has four doors, and each arrives here:
- no command (`docker run -p 8888:8888 IMAGE`, a dev container): one learner's lab, listening
  on the container's port 8888, which prints lesson 1's address with its token;
- a Jupyter server's command (Binder's and Zero to JupyterHub's `jupyterhub-singleuser ...`,
  or `jupyter lab ...`): that server, run as the learner's lab with the course's options;
- any other command (`bash`, `make doctor`) runs as it is.

The learner's work lives in their home (the volume the README names): their own copy of the
notebooks, made on the first start and never replaced (hub.singleuser.prepare_learner_copy).
"""

from __future__ import annotations

import os
import shutil
import sys
from collections.abc import Callable, Sequence
from pathlib import Path

from ..core.paths import LEARNER_ROOT_ENV, venv_bin_dir
from ..hub.singleuser import DEFAULT_URL, prepare_learner_copy, run_hub_lab
from ..lab.jupyterlab import course_server_options, run_lab

__all__ = ["IMAGE_PORT", "image_lab_argv", "main"]

IMAGE_PORT = 8888
_HUB_SERVERS = {"jupyterhub-singleuser"}
_LAB_SERVERS = {"jupyter-lab", "jupyter-notebook", "jupyter-server"}


def image_lab_argv(root: Path) -> Callable[[Sequence[str]], list[str]]:
    """Return the server's command line builder for one learner's lab in a container: every
    address of the container (the port is published to the host), lesson 1 first."""

    def argv(extra: Sequence[str]) -> list[str]:
        return [
            str(venv_bin_dir() / "jupyter"),
            "lab",
            "--no-browser",
            "--ServerApp.ip=0.0.0.0",
            f"--ServerApp.port={IMAGE_PORT}",
            f"--ServerApp.root_dir={root}",
            f"--LabApp.default_url={DEFAULT_URL}",
            *(["--allow-root"] if os.geteuid() == 0 else []),
            *course_server_options(),
            *extra,
        ]

    return argv


def _server_options(command: Sequence[str]) -> list[str] | None:
    """Return a Jupyter lab command's own options (None: not a lab's command)."""
    program = Path(command[0]).name
    if program in _LAB_SERVERS:
        return list(command[1:])
    if program == "jupyter" and len(command) > 1 and command[1] in ("lab", "notebook", "server"):
        return list(command[2:])
    return None


def run_image_lab(extra: Sequence[str] = ()) -> int:
    """Run one learner's lab on the container's port, their notebooks in their home."""
    root = prepare_learner_copy(Path.home())
    os.environ[LEARNER_ROOT_ENV] = str(root)  # the lessons write into the learner's my_files/
    return run_lab(extra, server_argv=image_lab_argv(root), cwd=root)


def main(command: Sequence[str]) -> int:
    """Run the image's command: the learner's lab (no command or a Jupyter server's), or the
    command itself."""
    if not command or command[0].startswith("-"):
        return run_image_lab(command)
    if Path(command[0]).name in _HUB_SERVERS:
        return run_hub_lab(command[1:])
    options = _server_options(command)
    if options is not None:
        return run_image_lab(options)
    program = shutil.which(command[0])
    if program is None:
        print(f"No command {command[0]!r} in the course's image.", file=sys.stderr)
        return 127
    os.execv(program, list(command))
