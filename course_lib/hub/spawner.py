"""The learners' servers: JupyterHub's local-process spawner, tied to the hub and cleaned after."""

from __future__ import annotations

import asyncio
import contextlib
import os
import pwd
import signal
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any, ClassVar
from urllib.parse import quote

from jupyterhub.spawner import LocalProcessSpawner, set_user_setuid
from traitlets import Bool, Int, List, Unicode

from ..core.errors import DomainUnavailableError
from ..core.host.signalling import send
from ..processes.domain import DOMAIN_ENV, candidate_domains, domain_in_use
from .guard.routes import forget_route, pin_route
from .guard.runtime_leftovers import account_identity, clear_for_account
from .guard.tied import tie_to_parent
from .guard.wall import Relay, enter_own_network

__all__ = ["CourseSpawner", "HubDomains", "leftover_stop_argv", "run_bounded"]

# jupyter_server refuses --sock beside any port but its default one; in a network of its own
# the server binds no port at all, so the hub names that one (JUPYTERHUB_SERVICE_URL).
_SERVER_DEFAULT_PORT = 8888


class HubDomains:
    """The ROS domain ids the hub has given to running servers: one per learner, held from
    the server's start to its stop, whatever other accounts bind (no port lease)."""

    def __init__(self) -> None:
        self._held: dict[str, int] = {}

    def take(self, name: str, *, walled: bool) -> int:
        """Return `name`'s domain id, the one they hold already or a new one."""
        if name in self._held:
            return self._held[name]
        taken = set(self._held.values())
        for domain_id in candidate_domains(1):
            # in a network of its own a lab meets no other DDS socket; without one, a domain
            # some process of the host already uses is passed over
            if domain_id not in taken and (walled or not domain_in_use(domain_id)):
                self._held[name] = domain_id
                return domain_id
        raise DomainUnavailableError(
            "Every ROS domain id on this host is in use.", hint="stop a server, then retry."
        )

    def give_back(self, name: str) -> None:
        self._held.pop(name, None)

    def held(self) -> dict[str, int]:
        return dict(self._held)


STOP_TIMEOUT_S = 60.0
START_POLL_S = 0.25
OUTPUT_LIMIT = 16384  # bytes of its output the hub keeps for its log


class CourseSpawner(LocalProcessSpawner):
    """Runs `python -m course_lib hub-lab` as the learner's Unix account.

    The server gets SIGTERM if the hub dies, and once it has stopped, the learner's leftover
    course processes (if any) are stopped the way `make stop` does, run as the learner.

    The hub gives each learner their ROS domain id for the server's life (`HubDomains`). With
    `wall` (the hub's default where the kernel allows it), the server starts in a network of
    its own (course_lib.hub.guard.wall): it listens on a Unix socket in `sockets_dir/<name>/`, a
    folder only the learner (and root) can enter, and the hub relays `relay_ports` (its API,
    the progress service) into that network.
    """

    wall = Bool(False, help="each server in a network namespace of its own").tag(config=True)
    sockets_dir = Unicode("", help="where each learner's server socket folder is").tag(config=True)
    relay_ports = List(Int(), help="host ports on 127.0.0.1 relayed into each lab").tag(
        config=True
    )
    state_dir = Unicode("", help="the hub's root-only state folder (runtime folders' record)").tag(
        config=True
    )

    domains: ClassVar[HubDomains] = HubDomains()
    _relay: Relay | None = None
    _network: int | None = None  # the inode of the lab's network namespace
    domain_id: int | None = None

    def make_preexec_fn(self, name: str) -> Callable[[], None]:
        become_user = set_user_setuid(name)
        hub = os.getpid()  # the parent, as it is now: a child that finds another is orphaned
        walled = self.wall

        def preexec() -> None:
            if walled:
                enter_own_network()  # as root, before the learner's uid
            become_user()
            tie_to_parent(parent=hub)  # after setuid: that clears the parent-death signal

        return preexec

    def socket_path(self) -> Path:
        """Return the Unix socket the learner's server listens on (with the wall)."""
        return Path(self.sockets_dir) / self.user.name / "server.sock"

    def _prepare_socket_folder(self) -> Path:
        account = pwd.getpwnam(self.user.name)
        folder = self.socket_path().parent
        folder.mkdir(mode=0o700, exist_ok=True)
        os.chown(folder, account.pw_uid, account.pw_gid)
        folder.chmod(0o700)
        self.socket_path().unlink(missing_ok=True)  # a killed server's
        return folder

    def get_args(self) -> list[str]:
        args = super().get_args()
        if self.wall:
            args.append(f"--ServerApp.sock={self.socket_path()}")
        return args

    def get_env(self) -> dict[str, str]:
        env = super().get_env()
        if self.domain_id is not None:
            env[DOMAIN_ENV] = str(self.domain_id)  # the lab takes it as given: no lease
        return env

    async def start(self) -> Any:
        self._clear_runtime_leftovers()
        self.domain_id = self.domains.take(self.user.name, walled=self.wall)
        if not self.wall:
            address = await super().start()
            await self._wait_until_listening()
            return address
        self._prepare_socket_folder()
        self.port = _SERVER_DEFAULT_PORT
        await super().start()
        self._network = os.stat(f"/proc/{self.pid}/ns/net").st_ino
        self._relay = Relay(self.pid, list(self.relay_ports), self.log.warning)
        await self._relay.start()
        await self._wait_until_listening()
        # routed to the socket the server listens on, whatever the learner's folder holds later
        route = pin_route(
            self.socket_path(), Path(self.sockets_dir), self.user.name, self._account().pw_uid
        )
        url = f"http+unix://{quote(str(route), safe='')}"
        # JupyterHub keeps only ip and port of a server; its address on a socket is this
        self.server.connect_url = url
        return url

    def _account(self) -> pwd.struct_passwd:
        return pwd.getpwnam(self.user.name)

    def _clear_runtime_leftovers(self) -> None:
        """Remove the runtime folders another account with the learner's uid left
        (course_lib.hub.guard.runtime_leftovers), as root, before their server starts."""
        if self.state_dir:
            uid, identity = account_identity(self.user.name)
            for removal in clear_for_account(uid, identity, Path(self.state_dir)):
                self.log.warning(removal.line())

    async def _wait_until_listening(self) -> None:
        """Return once the server accepts connections, or after `http_timeout` (the hub's own
        wait then says so); raise at once if it ends first. JupyterHub itself only asks
        whether the server answers, so a server that died as it started (a home the learner
        cannot write, say) kept the learner on "starting" for the whole timeout."""
        deadline = time.monotonic() + self.http_timeout
        while time.monotonic() < deadline:
            status = await self.poll()
            if status is not None:
                raise RuntimeError(
                    f"{self.user.name}'s server stopped as it started (exit status {status}): "
                    "its last lines are in the hub's log."
                )
            if await self._accepts_connections():
                return
            await asyncio.sleep(START_POLL_S)

    async def _accepts_connections(self) -> bool:
        try:
            if self.wall:
                _, writer = await asyncio.open_unix_connection(str(self.socket_path()))
            else:
                _, writer = await asyncio.open_connection(self.ip or "127.0.0.1", self.port)
        except OSError:
            return False
        writer.close()
        with contextlib.suppress(OSError):
            await writer.wait_closed()
        return True

    async def stop(self, now: bool = False) -> None:
        try:
            await super().stop(now=now)
        finally:
            self.release()

    def release(self) -> None:
        """Let go of what the hub holds for the server: the relay into its network (its
        sockets keep that network alive), its route, its domain id. Run by `stop` and by the
        post-stop hook: JupyterHub calls no `stop` for a server its poll found dead (killed,
        crashed), so without the hook the hub kept the relay's sockets until it ended."""
        if self._relay is not None:
            self._relay.close()
            self._relay = None
        if self.wall:
            forget_route(Path(self.sockets_dir), self.user.name)
        self.domains.give_back(self.user.name)

    async def stop_leftovers(self) -> None:
        """Run `python -m course_lib stop` as the learner; log what it stopped."""
        account = pwd.getpwnam(self.user.name)
        env = {"HOME": account.pw_dir, "USER": self.user.name, "PATH": self.environment["PATH"]}
        text = await run_bounded(
            leftover_stop_argv(self.cmd[0]), env=env, preexec_fn=set_user_setuid(self.user.name)
        )
        if text is None:
            self.log.warning("Stopping %s's leftover processes took too long", self.user.name)
            return
        self.log.info("After %s's server stopped: %s", self.user.name, text or "nothing left")
        if self._network is not None:  # the lab's network ends with it, as a pod would
            swept = sweep_network(self._network, pwd.getpwnam(self.user.name).pw_uid)
            if swept:
                self.log.info("Stopped what was left in %s's lab: %s", self.user.name, swept)
            self._network = None


def sweep_network(network: int, uid: int) -> list[int]:
    """SIGKILL every process of `uid` still in the network namespace whose inode is
    `network` (a learner's own programs, after their server stopped); return their pids.
    Both are checked for each process before the signal: nothing else is ever signalled."""
    swept = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            if entry.stat().st_uid != uid or os.stat(entry / "ns" / "net").st_ino != network:
                continue
            send(int(entry.name), signal.SIGKILL, reason="its lab's server stopped")
            swept.append(int(entry.name))
        except (OSError, ProcessLookupError):
            continue
    return swept


def leftover_stop_argv(python: str) -> list[str]:
    """Return `python -m course_lib stop`, isolated: nothing of the learner's is imported.

    `-I` leaves the current folder, PYTHON* variables and the user's site-packages out of the
    import path, so a `course_lib` folder the learner planted is never the one that runs.
    """
    return [python, "-I", "-m", "course_lib", "stop"]


async def run_bounded(
    argv: list[str],
    *,
    env: dict[str, str],
    preexec_fn: Callable[[], None] | None = None,
    timeout: float = STOP_TIMEOUT_S,
) -> str | None:
    """Run `argv` in `/`; return the start of its output (OUTPUT_LIMIT bytes), None if it hung."""
    process = await asyncio.create_subprocess_exec(
        *argv, preexec_fn=preexec_fn, env=env, cwd="/",
        stdout=asyncio.subprocess.PIPE, stderr=asyncio.subprocess.STDOUT,
    )  # fmt: skip
    stdout = process.stdout
    assert stdout is not None  # asked for: stdout=PIPE

    async def collect() -> bytes:
        kept = bytearray()
        while chunk := await stdout.read(65536):
            kept += chunk[: max(0, OUTPUT_LIMIT - len(kept))]  # the rest is read, not kept
        await process.wait()
        return bytes(kept)

    try:
        output = await asyncio.wait_for(collect(), timeout)
    except TimeoutError:
        send(process.pid, signal.SIGKILL, reason="`course_lib stop` after a server hung")
        await process.wait()
        return None
    return output.decode(errors="replace").strip()


async def stop_leftovers_hook(spawner: Any) -> None:
    """JupyterHub's post-stop hook, run after every stop, a server that died on its own
    included: see CourseSpawner.release and CourseSpawner.stop_leftovers."""
    spawner.release()
    await spawner.stop_leftovers()
