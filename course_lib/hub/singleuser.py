"""`python -m course_lib hub-lab`: a learner's server on the class hub, run as the learner.

It is `make lab` for one learner: their own copy of the notebooks in their home, one ROS
domain and one robot for all their kernels and terminals, and the Jupyter server the hub
expects (jupyterhub-singleuser, which takes the spawner's options).
"""

from __future__ import annotations

import os
import shutil
from collections.abc import Callable, Sequence
from pathlib import Path

from ..core.paths import LEARNER_ROOT_ENV, NOTEBOOKS_DIR, ROSJECT_DIR, venv_bin_dir
from ..lab.jupyterlab import course_server_options, run_lab

__all__ = ["DEFAULT_URL", "LEARNER_FOLDER", "prepare_learner_copy", "run_hub_lab"]

LEARNER_FOLDER = "ros2-params-course"  # in the learner's home
DEFAULT_URL = "/lab/tree/notebooks/01_setup_check.ipynb"


def prepare_learner_copy(home: Path) -> Path:
    """Give the learner their own notebooks in `home`; return the course folder there.

    Notebooks the learner already has are theirs and never replaced; new lessons are added.
    `rosject` links to the class's read-only workspace, so the lessons' `../rosject/...`
    paths work as in a clone.
    """
    root = home / LEARNER_FOLDER
    notebooks = root / "notebooks"
    (notebooks / "my_files").mkdir(parents=True, exist_ok=True)
    for lesson in sorted(NOTEBOOKS_DIR.glob("*.ipynb")):
        target = notebooks / lesson.name
        if not target.exists():
            shutil.copyfile(lesson, target)
    link = root / "rosject"
    if not link.is_symlink() and not link.exists():
        link.symlink_to(ROSJECT_DIR, target_is_directory=True)
    return root


def _singleuser_argv(root: Path) -> Callable[[Sequence[str]], list[str]]:
    def argv(extra: Sequence[str]) -> list[str]:
        return [
            str(venv_bin_dir() / "jupyterhub-singleuser"),
            f"--ServerApp.root_dir={root}",
            *course_server_options(),
            *extra,
        ]

    return argv


def run_hub_lab(extra: Sequence[str] = ()) -> int:
    """Prepare the learner's copy, then run their lab with jupyterhub-singleuser."""
    root = prepare_learner_copy(Path.home())
    os.environ[LEARNER_ROOT_ENV] = str(root)  # the lessons write into the learner's my_files/
    return run_lab(
        extra,
        server_argv=_singleuser_argv(root),
        cwd=root,
        name="jupyterhub-singleuser",
        restart_killed=False,  # the hub shows it stopped; "Start My Server" brings it back
    )
