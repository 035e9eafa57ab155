"""`make doctor`: what is installed, what is stale and what runs (it changes nothing).

It also proves the install works, each in a child process of its own (a crash or a hang
there is a failed check, not a dead doctor): rclpy starts with its middleware, the course's
workspace gives `tf2_msgs`, and the simulation renders its camera offscreen. `make doctor`
exits non-zero when one of them fails, so the image's build (the Dockerfile, `make image`)
stops on a broken install.
"""

from __future__ import annotations

import os
import platform
import shutil
import subprocess
import sys
from dataclasses import dataclass
from importlib import metadata
from pathlib import Path

from ..core import ament
from ..core.paths import REPO_ROOT
from ..processes.ownership import course_processes

__all__ = ["Check", "install_checks", "report", "stale_steps"]

# The Makefile's set-up steps: its target, and what `make setup` would do when it is stale.
_SETUP_STEPS = (
    (".venv/.installed", "environment (.venv)", "reinstalls the Python packages"),
    ("rosject/install/.built", "ROS workspace (rosject/install)", "rebuilds it with colcon"),
)

_DISTRIBUTIONS = (
    "ros-jazzy-rclpy",
    "ros-jazzy-rmw-fastrtps-cpp",
    "mujoco",
    "meshcat",
    "jupyterlab",
)


CHECK_TIMEOUT_S = 60.0

# What each check runs in a fresh interpreter; the last line it prints is the evidence.
_RCLPY = """
import rclpy
context = rclpy.Context()
rclpy.init(context=context)
from rclpy.utilities import get_rmw_implementation_identifier
print(get_rmw_implementation_identifier())
rclpy.shutdown(context=context)
"""
_TF2_MSGS = """
from course_lib.core import ament
ament.use_workspace_interfaces()
from tf2_msgs.msg import TFMessage
from rclpy.serialization import serialize_message
print(f"TFMessage serialises to {len(serialize_message(TFMessage()))} bytes")
"""
_RENDERING = """
import os
os.environ.setdefault("MUJOCO_GL", "egl")
import mujoco
from course_lib.config.simulation import SimulationSettings
from course_lib.sim.ros.camera import CAMERA_NAME
from course_lib.sim.world.model import build_model
model = build_model(SimulationSettings())
data = mujoco.MjData(model)
mujoco.mj_forward(model, data)
renderer = mujoco.Renderer(model, 48, 64)
renderer.update_scene(data, camera=CAMERA_NAME)
pixels = renderer.render()
renderer.close()
if not pixels.any():
    raise SystemExit("the camera's image is all black")
size = f"{pixels.shape[1]}x{pixels.shape[0]}"
print(f"camera {size} rendered with MUJOCO_GL={os.environ['MUJOCO_GL']}")
"""
_CHECKS = (
    ("rclpy", _RCLPY, "rclpy and its middleware (make setup reinstalls them)"),
    ("tf2_msgs", _TF2_MSGS, "tf2_msgs from the workspace (make setup builds rosject/)"),
    ("rendering", _RENDERING, "the simulation's offscreen camera (EGL: libegl1, Mesa)"),
)


@dataclass(frozen=True)
class Check:
    """One proof that a part of the install works: its name, verdict and one line."""

    name: str
    ok: bool
    line: str

    def render(self) -> str:
        return f"{'ok' if self.ok else 'FAILED'}: {self.name}: {self.line}"


def _run_check(name: str, code: str, what: str, env: dict[str, str]) -> Check:
    try:
        done = subprocess.run(
            [sys.executable, "-c", code], cwd=REPO_ROOT, env=env, capture_output=True,
            text=True, timeout=CHECK_TIMEOUT_S, check=False,
        )  # fmt: skip
    except subprocess.TimeoutExpired:
        return Check(name, False, f"no answer in {CHECK_TIMEOUT_S:.0f} s; {what}")
    out = (done.stdout.strip().splitlines() or [""])[-1]
    if done.returncode == 0 and out:
        return Check(name, True, out)
    error = (done.stderr.strip().splitlines() or [f"exit {done.returncode}"])[-1]
    return Check(name, False, f"{error[:200]} ({what})")


def install_checks() -> list[Check]:
    """Return whether rclpy, tf2_msgs and the simulation's rendering work here."""
    from concurrent.futures import ThreadPoolExecutor

    env = {**os.environ, "PYTHONPATH": str(REPO_ROOT)}  # this course, from any folder
    with ThreadPoolExecutor(len(_CHECKS)) as pool:  # each waits on a child: side by side
        running = [pool.submit(_run_check, *check, env) for check in _CHECKS]
        return [future.result() for future in running]


def _version(dist: str) -> str:
    try:
        return metadata.version(dist)
    except metadata.PackageNotFoundError:
        return "missing (run `make setup`)"


def stale_steps(repo: Path = REPO_ROOT) -> list[str]:
    """Return one line per set-up step: up to date, or stale (asks `make -q`, changes nothing)."""
    if shutil.which("make") is None or not (repo / "Makefile").exists():
        return ["set-up steps: unknown (no make or no Makefile here)"]
    lines = []
    for target, what, redo in _SETUP_STEPS:
        result = subprocess.run(
            ["make", "-q", target], cwd=repo, capture_output=True, check=False, timeout=60
        )
        state = "up to date" if result.returncode == 0 else f"stale: `make setup` {redo}"
        lines.append(f"{what}: {state}")
    return lines


def report(checks: list[Check] | None = None) -> str:
    """Return a short text of the machine, the installed stack, the install's checks (see
    `install_checks`) and the running processes."""
    lines = [f"Python {platform.python_version()} on {platform.system()} {platform.machine()}"]
    lines += [f"{dist}: {_version(dist)}" for dist in _DISTRIBUTIONS]
    packages = ament.list_packages(ament.workspace_env({}))
    lines.append(f"workspace packages: {', '.join(sorted(packages)) or 'none (run `make setup`)'}")
    lines += stale_steps()
    lines += [check.render() for check in checks or []]
    lines.append(f"ROS_DOMAIN_ID: {os.environ.get('ROS_DOMAIN_ID', 'not set')}")
    running = course_processes()  # the same rule `make stop` uses
    lines.append(f"course processes running: {len(running)}")
    lines += [f"  {p.pid} {p.name}: {' '.join(p.info.argv)[:90]}" for p in running]
    return "\n".join(lines)
