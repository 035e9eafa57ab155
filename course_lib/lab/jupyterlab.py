"""`make lab`: JupyterLab on lesson 1, in one ROS domain shared by kernels and terminals."""

from __future__ import annotations

import json
import os
import shutil
import signal
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from ..core.host.procfs import start_time
from ..core.paths import NOTEBOOKS_DIR, PACKAGE_DIR, REPO_ROOT, runtime_dir, venv_bin_dir
from ..core.server_urls import SERVER_ROOT_ENV
from ..processes.children import ChildProcess, spawn
from ..processes.domain import lease_domain
from ..processes.lab_markers import lab_clone_marker, lab_marker, lab_start_marker
from ..processes.shm_segments import sweep_stale_segments
from ..session.session import session_env
from .leftovers import clean_up_killed_labs, workspaces_dir
from .protocol import SOCKET_ENV
from .server_restarts import ServerRestarts, argv_with

__all__ = [
    "FIRST_LESSON",
    "LAB_BASHRC",
    "course_server_options",
    "lab_argv",
    "run_lab",
    "terminal_shell_command",
]

FIRST_LESSON = "notebooks/01_setup_check.ipynb"
LAB_BASHRC = PACKAGE_DIR / "shell" / "lab_bashrc.bash"


LAB_SETTINGS_DIR = PACKAGE_DIR / "lab_settings"
LAB_EXTENSIONS_DIR = PACKAGE_DIR / "lab_extensions"


def course_server_options() -> list[str]:
    """Return the Jupyter server options every lab of the course runs with (local or hub)."""
    return [
        # A login shell would re-read /etc/profile and drop .venv/bin (and `ros2`) from PATH.
        f"--ServerApp.terminado_settings={_terminal_settings()}",
        # A notebook whose kernel was shut down starts its own (Python 3) when a cell runs,
        # without asking (the course's defaults, overrides.json), and Run All then runs every
        # cell: the course's plugin makes the start single-flight (lab_extensions/: why).
        f"--LabApp.app_settings_dir={LAB_SETTINGS_DIR}",
        f"--LabApp.extra_labextensions_path={LAB_EXTENSIONS_DIR}",
        # a saved notebook keeps no live 3D view or widget (they would show errors reopened)
        "--ContentsManager.pre_save_hook=course_lib.core.files.live_outputs.scrub_on_save",
        # Where Node.js is installed (a hub host has it for its proxy), JupyterLab ran it per
        # server start and page load: `npm prefix -g` (jupyter-lsp looking for language
        # servers: the course ships none) and, for the page's build check (off in
        # lab_settings/page_config.json: the course's extensions come prebuilt),
        # `node-version-check` and `yarn config`. About 1.6 CPU-s on a busy 2-core host.
        "--LanguageServerManager.autodetect=False",
        # one ill-sized websocket message cost a server 3 GiB (kernel_socket.py: why)
        "--ServerApp.kernel_websocket_connection_class="
        "course_lib.lab.kernel_socket.CourseKernelConnection",
    ]


def lab_argv(extra: Sequence[str] = ()) -> list[str]:
    """Return the JupyterLab command line: loopback only, the first lesson open.

    Lesson 1 is the server's default URL, so the address it prints (`--no-browser`, for a
    learner on a remote machine to paste) and the one the browser opens are lesson 1's.
    """
    first = FIRST_LESSON if (REPO_ROOT / FIRST_LESSON).exists() else NOTEBOOKS_DIR.name
    return [
        str(venv_bin_dir() / "jupyter"),
        "lab",
        "--ServerApp.ip=127.0.0.1",
        f"--ServerApp.root_dir={REPO_ROOT}",
        f"--LabApp.default_url=/lab/tree/{first}",
        *(["--allow-root"] if os.geteuid() == 0 else []),  # containers and CI run as root
        *course_server_options(),
        *extra,
    ]


def terminal_shell_command() -> list[str]:
    """Return the lab terminal's shell: the user's, interactive; bash reads the course's rc.

    The rc (course_lib/shell/lab_bashrc.bash) reads ~/.bashrc as bash would, and answers the
    docs' `source /opt/ros/jazzy/setup.bash` in one line: the lab is already set up.
    """
    shell = os.environ.get("SHELL") or "/bin/bash"
    if Path(shell).name == "bash":
        return [shell, "--rcfile", str(LAB_BASHRC), "-i"]
    return [shell, "-i"]


def _terminal_settings() -> str:
    """Return terminado settings that start the user's shell as a plain interactive shell."""
    return json.dumps({"shell_command": terminal_shell_command()})


def _start_machine(env: dict[str, str], cwd: Path) -> Any:
    """Start the lab's machine service: it owns the world every notebook of the lab shares."""
    from .daemon_keeper import DaemonKeeper
    from .service import MachineService

    def spawn_in_lab(argv: Sequence[str], *, name: str) -> ChildProcess:
        return spawn(argv, name=name, env=env, cwd=cwd)

    path = runtime_dir() / f"lab-{os.getpid()}.sock"
    return MachineService(path, spawn_in_lab, DaemonKeeper(spawn_in_lab, env)).start()


def run_lab(
    extra: Sequence[str] = (),
    *,
    server_argv: Callable[[Sequence[str]], list[str]] = lab_argv,
    cwd: Path = REPO_ROOT,
    name: str = "jupyterlab",
    restart_killed: bool = True,
) -> int:
    """Start JupyterLab in a leased domain (its ros2 daemon with its first terminal, see
    lab.daemon_keeper); stop them on Ctrl-C.

    `server_argv` builds the Jupyter server's command line from the extra options (a hub's
    learner runs jupyterhub-singleuser instead of jupyter lab), run in `cwd`: the folder it
    serves (its `root_dir`). With `restart_killed`, a server killed by a signal (the
    out-of-memory killer) is started again at its address (`ServerRestarts`); a hub's learner
    server is the hub's to start again.
    """
    for note in (clean_up_killed_labs(), sweep_stale_segments().sentence()):
        if note:
            print(note)
    lease = lease_domain()
    started = lab_start_marker(os.getpid())
    started.write_text(start_time(os.getpid()) or "")  # first: it vouches for the others
    marker = lab_marker(os.getpid())
    marker.write_text(str(lease.domain_id))
    clone = lab_clone_marker(os.getpid())
    clone.write_text(str(REPO_ROOT))
    env = session_env(lease.domain_id)
    env["COURSE_LAB"] = "1"
    env[SERVER_ROOT_ENV] = str(cwd)  # the folder the server serves: kernels link files in it
    machine = _start_machine(env, cwd)
    env[SOCKET_ENV] = str(machine.path)
    print(
        f"ROS 2 course: ROS_DOMAIN_ID={lease.domain_id} for this JupyterLab and its terminals.",
        flush=True,
    )
    signal.signal(signal.SIGTERM, signal.default_int_handler)  # stop cleanly on SIGTERM too
    # A workspace folder of its own: lesson 1 opens without the tabs of earlier labs or tests.
    workspaces = workspaces_dir(os.getpid())
    workspaces.mkdir(mode=0o700, exist_ok=True)
    argv = server_argv([f"--LabApp.workspaces_dir={workspaces}", *extra])
    lab = spawn(argv, name=name, env=env, cwd=cwd, capture=False)
    restarts = ServerRestarts(env)
    try:
        while True:
            code = lab.wait()
            again = restarts.argv_again(lab.pid, code) if restart_killed else None
            if again is None:
                break
            lab = spawn(argv_with(argv, again), name=name, env=env, cwd=cwd, capture=False)
    except KeyboardInterrupt:
        lab.send_signal(signal.SIGTERM)
        code = lab.wait(10.0)
    finally:
        lab.stop(timeout=5.0)
        machine.stop()  # the world and the ros2 daemon with it
        marker.unlink(missing_ok=True)
        clone.unlink(missing_ok=True)
        started.unlink(missing_ok=True)
        shutil.rmtree(workspaces, ignore_errors=True)
        lease.release()
    return code or 0
