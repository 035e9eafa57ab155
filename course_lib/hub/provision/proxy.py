"""The hub's proxy, configurable-http-proxy, installed from npm at the version pinned here."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

from ...core.errors import CourseError
from ...core.host.procfs import start_time
from ..guard.locks import hub_lock

__all__ = [
    "PINS_DIR",
    "PROXY_API_SOCKET",
    "forget_stale_proxy",
    "forget_stale_proxy_pid",
    "install_proxy",
    "missing_npm",
    "proxy_argv",
    "proxy_command",
]

PINS_DIR = Path(__file__).resolve().parent / "proxy"  # package.json and its lock file
# loaded into the proxy: keep-alive connections to Unix-socket targets (read its comment)
PRELOAD = "unix_keepalive.mjs"
_PINNED = ("package.json", "package-lock.json", PRELOAD)
# The proxy's API (its token goes there with every call), on a Unix socket in the hub's state
# folder, root's alone: no port another account could bind first, or after the proxy died.
PROXY_API_SOCKET = "proxy-api.sock"


def proxy_command(environment: Path) -> Path:
    """Return where the proxy's command is once installed under `environment`."""
    return environment / "proxy" / "node_modules" / ".bin" / "configurable-http-proxy"


def proxy_argv(command: str | Path) -> list[str]:
    """Return the command line that runs the installed proxy `command` (proxy_command's path,
    kept as it is: the launcher knows the proxy by it) with the course's preload."""
    preload = Path(command).parents[2] / PRELOAD  # environment/proxy/, beside node_modules/
    return [shutil.which("node") or "node", "--import", preload.as_uri(), str(command)]


def missing_npm() -> CourseError | None:
    """Return the error to raise when npm is needed and missing, else None."""
    if shutil.which("npm") is not None and shutil.which("node") is not None:
        return None
    return _missing_npm()


def _missing_npm() -> CourseError:
    return CourseError(
        "npm is missing: the hub's proxy (configurable-http-proxy) is installed with npm.",
        hint="install Node.js and npm (`apt-get install nodejs npm`), then run `make hub` again.",
    )


def install_proxy(environment: Path) -> Path:
    """Install the pinned proxy under `environment/proxy` (again only when the pins changed);
    return the path of its command. One install at a time: two `npm ci` in one folder (two
    hubs started at once on a fresh host) fail each other."""
    environment.mkdir(parents=True, exist_ok=True)
    with hub_lock(environment, "proxy", "the install of the hub's proxy"):
        return _install_locked(environment)


def _install_locked(environment: Path) -> Path:
    folder = environment / "proxy"
    command = proxy_command(environment)
    same = all(
        (folder / name).exists() and (folder / name).read_bytes() == (PINS_DIR / name).read_bytes()
        for name in _PINNED
    )
    if same and command.exists():
        return command
    problem = missing_npm()
    if problem is not None:
        raise problem
    npm = str(shutil.which("npm"))
    folder.mkdir(parents=True, exist_ok=True)
    for name in _PINNED:
        shutil.copyfile(PINS_DIR / name, folder / name)
    result = subprocess.run(
        [npm, "ci", "--no-audit", "--no-fund", "--loglevel=error"],
        cwd=folder,
        capture_output=True,
        text=True,
        check=False,
    )
    if result.returncode != 0 or not command.exists():
        raise CourseError(
            f"npm could not install configurable-http-proxy in {folder}:\n{result.stderr.strip()}",
            hint="check that this host reaches the npm registry, then run `make hub` again.",
        )
    return command


def _boot_time() -> float:
    for line in Path("/proc/stat").read_text().splitlines():
        if line.startswith("btime "):
            return float(line.split()[1])
    return 0.0


def forget_stale_proxy_pid(pid_file: Path, proxy: Path) -> str | None:
    """Remove `pid_file` unless it names the hub's own proxy, still running; return one line
    saying what was left alone, or None.

    JupyterHub stops (SIGTERM, then SIGKILL, as root) whatever process the proxy's pid file
    names when it starts. After a hub was killed, that pid may be anyone's by now: only a
    process that runs this proxy and started before the file was written is the old proxy.
    """
    try:
        text = pid_file.read_text().strip()
        written = pid_file.stat().st_mtime
    except OSError:
        return None
    pid = int(text) if text.isdigit() else 0
    started = start_time(pid) if pid > 0 else None
    if started is not None:
        try:
            command = Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode()
        except OSError:
            command = ""
        began = _boot_time() + int(started) / os.sysconf("SC_CLK_TCK")
        if str(proxy) in command and began <= written + 1.0:
            return None  # the killed hub's own proxy: JupyterHub stops it
    pid_file.unlink(missing_ok=True)
    if started is None:
        return None
    return f"{pid_file} named pid {pid}, which is not the hub's proxy any more: it is left alone."


def forget_stale_proxy(state: Path, proxy: Path) -> str | None:
    """Forget what a killed hub's proxy left in `state` (forget_stale_proxy_pid; its API
    socket, unless JupyterHub is to stop that proxy and remove it); return the one line to
    say, or None."""
    note = forget_stale_proxy_pid(state / "proxy.pid", proxy)
    if not (state / "proxy.pid").exists():  # a socket file nobody listens on: the proxy's
        (state / PROXY_API_SOCKET).unlink(missing_ok=True)  # start would fail on it
    return note
