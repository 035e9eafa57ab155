"""A real class hub for the tests: `python -m course_lib hub` with test learners (needs root).

The learners' environment is built once per clone in the temp folder (make's stamps make a
second run quick); the hub's state, the accounts and every process are the test's own and are
removed after it.
"""

from __future__ import annotations

import contextlib
import ctypes
import errno
import fcntl
import hashlib
import os
import pwd
import shutil
import signal
import subprocess
import tempfile
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from suite_env import independent_env
from unix_accounts import new_home
from waits import POLL_MS

from course_lib.core.host.ports import free_port
from course_lib.core.paths import REPO_ROOT
from course_lib.core.waiting import wait_until
from course_lib.processes.children import ChildProcess, spawn

__all__ = [
    "ClassHub",
    "hub_environment",
    "process_tree",
    "processes_of",
    "server_pid",
    "server_token",
    "sockets_in_network",
    "start_prebuild",
    "uid_of",
]

BUILD_TIMEOUT_S = 1200.0  # the first build of the learners' environment (pip, colcon)


def uid_of(name: str) -> int | None:
    try:
        return pwd.getpwnam(name).pw_uid
    except KeyError:
        return None


def _processes_of(name: str) -> Iterator[Path]:
    """Yield the /proc folder of every process running as Unix user `name`."""
    uid = uid_of(name)
    for entry in Path("/proc").iterdir():
        with contextlib.suppress(OSError):
            if entry.name.isdigit() and entry.stat().st_uid == uid:
                yield entry


def processes_of(name: str) -> list[str]:
    """Return `pid command` of every process running as Unix user `name`."""
    found = []
    for entry in _processes_of(name):
        with contextlib.suppress(OSError):
            command = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode()[:160]
            found.append(f"{entry.name} {command}")
    return found


def remove_account(name: str) -> None:
    """Remove a test account and its home (its processes first: it is the test's own); a home
    an interrupted run left without its account too (the hub refuses to create one over it)."""
    uid = uid_of(name)
    if uid is None:
        shutil.rmtree(new_home(name), ignore_errors=True)
        return
    for line in processes_of(name):
        with contextlib.suppress(OSError):
            os.kill(int(line.split(" ", 1)[0]), signal.SIGKILL)
    subprocess.run(["userdel", "--remove", name], check=False, capture_output=True)


def hub_environment() -> Path:
    """Return where the tests build the learners' environment (one per clone, kept)."""
    digest = hashlib.sha1(str(REPO_ROOT).encode()).hexdigest()[:10]
    return Path(tempfile.gettempdir()) / f"ros2-course-hub-env-{digest}"


# Ahead of the tests' processes (root may): on 2 busy cores the build took 146-215 s instead
# of 46, and the hub tests' workers waited for it, idle, while every other one had work. The
# build is a session of its own, so with autogroups (Linux's default for desktops and this
# kind of machine) the CPU is shared by session first: the niceness that counts is the
# session's (/proc/self/autogroup), its processes' only orders them within it.
PREBUILD_NICENESS = -10
_AHEAD = (
    "import os\n"
    "if os.geteuid() == 0:\n"
    f"    os.nice({PREBUILD_NICENESS})\n"
    "    try:\n"
    "        with open('/proc/self/autogroup', 'w') as group:\n"
    f"            group.write('{PREBUILD_NICENESS}')\n"
    "    except OSError:\n"
    "        pass  # a kernel without autogroups\n"
)


def start_prebuild() -> ChildProcess:
    """Start building the learners' environment and installing the hub's proxy now, while
    other tests run (their locks make a hub's own build and install wait for them, then find
    nothing left to do; a hub in a network of its own reaches no registry)."""
    code = _AHEAD + (
        "import sys; from pathlib import Path\n"
        "from course_lib.hub.provision.environment import build_environment\n"
        "from course_lib.hub.provision.proxy import install_proxy\n"
        "build_environment(Path(sys.argv[1]), Path(sys.argv[2]))\n"
        "install_proxy(Path(sys.argv[1]))\n"
    )
    python = "/usr/bin/python3.11"  # the hub's default interpreter (config/hub.yaml)
    argv = [str(REPO_ROOT / ".venv/bin/python"), "-c", code, str(hub_environment()), python]
    return spawn(argv, name="hub-prebuild", env=independent_env(), cwd=REPO_ROOT)


class ClassHub:
    """The course's hub on a free port, for `learners` and `admins` (test accounts).

    Options: `course`, the clone `python -m course_lib hub` runs from (the learners' copy is
    made from it); `config`, where the hub's settings are written (an existing file keeps its
    mode), `settings` added to them; `before_start`, run once the accounts are gone and before
    the hub starts (to make an account as an administrator did before the hub).
    """

    def __init__(
        self,
        learners: tuple[str, ...],
        admins: tuple[str, ...],
        folder: Path,
        env_extra: dict[str, str] | None = None,
        *,
        course: Path = REPO_ROOT,
        config: Path | None = None,
        settings: str = "",
        before_start: Callable[[], None] | None = None,
    ) -> None:
        self.learners, self.admins = learners, admins
        for name in (*learners, *admins):
            remove_account(name)  # a leftover of an interrupted run: start from nothing
        if before_start is not None:
            before_start()
        self.environment = hub_environment()
        # the progress service's account keeps its records beside the state: every parent
        # folder must let other accounts through (pytest's own temporary folder does not)
        self._open_parent = Path(tempfile.mkdtemp(prefix="ros2-course-hub-"))
        self._open_parent.chmod(0o711)
        self.state = self._open_parent / "state"
        if (folder / "state").is_dir():  # a state a test laid out (a stale pid file, ...)
            shutil.copytree(folder / "state", self.state)
        self.port = free_port()
        self.config = config or folder / "hub.yaml"
        self.config.write_text(
            f"learners: [{', '.join(learners)}]\nadmins: [{', '.join(admins)}]\n"
            f"port: {self.port}\nenvironment: {self.environment}\nstate: {self.state}\n"
            f"idle_minutes: 0\n{settings}",
            encoding="utf-8",
        )
        argv = [str(REPO_ROOT / ".venv/bin/python"), "-m", "course_lib", "hub"]
        # the hub and JupyterHub's settings run `course`'s course_lib (the current folder
        # comes first for `-m`; PYTHONPATH reaches the jupyterhub it starts)
        course_env = {} if course == REPO_ROOT else {"PYTHONPATH": str(course)}
        self.process: ChildProcess = spawn(
            [*argv, "--config", str(self.config)], name="class-hub",
            env={**independent_env(), **course_env, **(env_extra or {})},
            cwd=course, merge_stderr=True,
        )  # fmt: skip
        self.url = f"http://127.0.0.1:{self.port}"
        try:
            up = self.process.wait_for_line("The class hub is up", timeout=BUILD_TIMEOUT_S)
        except Exception as err:
            self.stop()
            raise AssertionError(f"the hub did not start:\n{self.process.text()[-4000:]}") from err
        if up is None:  # it ended (or never said so)
            self.stop()
            raise AssertionError(f"the hub did not start:\n{self.process.text()[-4000:]}")
        listed = self.state / "passwords.txt"  # none with one shared password
        lines = listed.read_text(encoding="utf-8").splitlines() if listed.exists() else []
        self.passwords = dict(line.split(" ", 1) for line in lines)

    def log(self) -> str:
        """Return what the hub printed (its own log and JupyterHub's)."""
        return self.process.text()

    def jupyterhub_pid(self) -> int:
        """Return the pid of JupyterHub itself (`python -m jupyterhub`, the hub's child)."""
        for pid in process_tree(self.process.pid):
            with contextlib.suppress(OSError):
                if b"\0-m\0jupyterhub\0" in Path(f"/proc/{pid}/cmdline").read_bytes():
                    return pid
        raise AssertionError(f"JupyterHub is not running:\n{self.log()[-2000:]}")

    def login(self, browser: Any, name: str) -> Any:
        """Sign `name` in through the hub's login form in a fresh browser context; return the
        page, on the server the hub started for them."""
        context = browser.new_context(viewport={"width": 1280, "height": 1000})
        page = context.new_page()
        page.goto(f"{self.url}/hub/login")
        page.fill("#username_input", name)
        page.fill("#password_input", self.passwords[name])
        page.click("#login_submit")
        if name in self.learners:
            page.wait_for_url(f"**/user/{name}/lab/**", timeout=180_000)
        return page

    def stop(self) -> dict[str, list[str]]:
        """Stop the hub as Ctrl-C does, remove the test accounts; return the processes each
        account still had once the hub had stopped (none, when all is well)."""
        if self.process.alive:
            self.process.send_signal(signal.SIGINT)
            self.process.wait(120.0)
        self.process.stop(timeout=5.0)
        accounts = (*self.learners, *self.admins)
        # a process that has ended but is not reaped yet (no command line: its parent, ending
        # too, has not waited for it) is not one that outlived the hub: give them a moment
        wait_until(lambda: not any(processes_of(name) for name in accounts), 10.0)
        left = {name: processes_of(name) for name in accounts}
        for name in (*self.learners, *self.admins):
            remove_account(name)
        shutil.rmtree(self._open_parent, ignore_errors=True)
        return {name: found for name, found in left.items() if found}


def stop_own_server(page: Any, hub_url: str) -> None:
    """Press "Stop My Server" on the hub's home page as a learner does: again if the first
    press came before the page's script had bound the button (it does nothing until then:
    seen once on a busy host, no stop request in 30 s)."""
    from playwright.sync_api import TimeoutError as PlaywrightTimeout

    page.goto(f"{hub_url}/hub/home")
    for _ in range(30):
        page.locator("#stop").click()
        try:
            page.wait_for_function(_STOP_TAKEN, timeout=2_000, polling=POLL_MS)
            return
        except PlaywrightTimeout:
            continue  # not bound yet: press again
    raise AssertionError("the hub's home page never took the click on Stop My Server")


# What the home page's click handler does at once (disables "My Server") and once the hub
# has stopped the server (that button then says "Start My Server").
_STOP_TAKEN = """() => {
  const start = document.querySelector('#start');
  if (start === null) return false;
  return start.hasAttribute('disabled') || /Start My Server/.test(start.innerText);
}"""


def server_token(name: str) -> str:
    """Return the hub API token that `name`'s server and kernels hold (root reads it)."""
    for entry in _processes_of(name):
        with contextlib.suppress(OSError):
            for item in (entry / "environ").read_bytes().split(b"\0"):
                if item.startswith(b"JUPYTERHUB_API_TOKEN="):
                    return item.split(b"=", 1)[1].decode()
    raise AssertionError(f"no process of {name} holds a hub token")


def server_pid(name: str) -> int | None:
    """Return the pid of `name`'s server as the hub started it (`python -m course_lib
    hub-lab`, run as `name`), or None when none runs."""
    for entry in _processes_of(name):
        with contextlib.suppress(OSError):
            argv = (entry / "cmdline").read_bytes().split(b"\0")
            if argv[1:4] == [b"-m", b"course_lib", b"hub-lab"]:
                return int(entry.name)
    return None


def process_tree(pid: int) -> set[int]:
    """Return `pid` and every process descending from it."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        with contextlib.suppress(OSError, ValueError, IndexError):
            if entry.name.isdigit():
                # the parent is the 2nd field after the command, which may hold spaces
                parent = int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
                children.setdefault(parent, []).append(int(entry.name))
    tree: set[int] = set()
    todo = [pid]
    while todo:
        current = todo.pop()
        tree.add(current)
        todo.extend(children.get(current, []))
    return tree


_PIDFD_GETFD = 438  # syscall number, one for every architecture (Linux 5.6)
_SIOCGSKNS = 0x894C  # ioctl: the network namespace of a socket, as a new fd


def sockets_in_network(holder: int, network: int) -> int:
    """Return how many sockets process `holder` has open in the network namespace whose
    inode is `network` (root: the sockets are copied out of `holder` to be asked). A socket
    keeps its namespace alive after the last process in it has ended."""
    libc = ctypes.CDLL(None, use_errno=True)
    pidfd = os.pidfd_open(holder)
    found = 0
    try:
        for entry in Path(f"/proc/{holder}/fd").iterdir():
            with contextlib.suppress(FileNotFoundError):  # closed meanwhile
                if not os.readlink(entry).startswith("socket:"):
                    continue
            fd = libc.syscall(_PIDFD_GETFD, pidfd, int(entry.name), 0)
            if fd < 0:
                if ctypes.get_errno() == errno.EBADF:  # closed meanwhile
                    continue
                raise OSError(ctypes.get_errno(), f"pidfd_getfd of {holder}'s fd {entry.name}")
            try:
                namespace = fcntl.ioctl(fd, _SIOCGSKNS)
                found += os.fstat(namespace).st_ino == network
                os.close(namespace)
            finally:
                os.close(fd)
    finally:
        os.close(pidfd)
    return found
