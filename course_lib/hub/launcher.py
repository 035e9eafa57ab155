"""`make hub` (`python -m course_lib hub`): check everything, build, then run the class hub."""

from __future__ import annotations

import contextlib
import os
import secrets
import signal
import socket
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
from pathlib import Path

import yaml

from ..core.errors import ConfigError, CourseError
from ..core.host.procfs import pid_namespace
from ..core.host.signalling import send
from ..processes.orphans import owner_alive, owner_tag
from .guard.gate import BACKLOG, Door, Gate, open_files_limit, unix_listener
from .guard.runtime_leftovers import remove_orphaned_folders
from .guard.tied import tied_preexec
from .guard.tree_removal import remove_tree
from .guard.wall import wall_problem
from .plan import HUB_SOCKET, PLAN_ENV, PROGRESS_SOCKET, PROXY_SOCKET, HubPlan, write_plan
from .progress import service_environment
from .progress_service import (
    SERVICE_ACCOUNT,
    KeptService,
    records_folder,
    start_service,
)
from .provision.accounts import ensure_accounts, ensure_system_account, refuse_system_accounts
from .provision.environment import build_environment, check_world_executable
from .provision.proxy import (
    PROXY_API_SOCKET,
    forget_stale_proxy,
    install_proxy,
    missing_npm,
    proxy_command,
)
from .provision.settings import HUB_YAML, HubSettings, load_hub_settings

__all__ = ["forget_stale_wall_folders", "run_hub"]

CONFIG_FILE = Path(__file__).resolve().parent / "jupyterhub_config.py"
READY_TIMEOUT_S = 60.0
STOP_TIMEOUT_S = 90.0  # the hub stops every learner's server first
NO_WALL_ENV = "COURSE_HUB_NO_WALL"  # set: no network of their own for learners (bench, tests)
WALL_PREFIX = "ros2-params-course-hub-"  # + the hub's port: its learners' socket folders
# In that folder (no account's name starts with a dot): the owner tag of the hub that made
# it, and its PID namespace.
WALL_OWNER = ".hub-owner"
_UNIX_PATH_MAX = 107  # bytes of a Unix socket's path (sun_path holds 108, with its NUL)


def _key_line(path: Path, key: str) -> int | None:
    """Return the line of top-level `key` in the YAML file `path`, if it is there."""
    with contextlib.suppress(OSError, yaml.YAMLError):
        root = yaml.compose(path.read_text(encoding="utf-8"), Loader=yaml.SafeLoader)
        for key_node, _ in getattr(root, "value", []):
            if key_node.value == key:
                return key_node.start_mark.line + 1
    return None


def _check_port(settings: HubSettings, source: Path) -> None:
    """Refuse a public port something listens on; connections of a hub stopped moments ago
    (TIME_WAIT) do not count (SO_REUSEADDR)."""
    _hold_port(settings, source).close()


def _hold_port(settings: HubSettings, source: Path) -> socket.socket:
    """Return the public port, listening (the gate serves it), or raise as _check_port."""
    family = socket.AF_INET6 if ":" in settings.ip else socket.AF_INET
    dual = settings.ip == "::" and socket.has_dualstack_ipv6()
    try:
        address = (settings.ip, settings.port)
        return socket.create_server(address, family=family, backlog=BACKLOG, dualstack_ipv6=dual)
    except OSError as err:
        raise ConfigError(
            str(source),
            _key_line(source, "port"),
            "port",
            f"port {settings.port} on {settings.ip} cannot be used: {err.strerror}",
            "stop what listens there, or set another `port:`.",
        ) from None


def _check_state(settings: HubSettings, source: Path) -> None:
    socket_path = os.fsencode(Path(settings.state) / PROXY_API_SOCKET)
    if len(socket_path) > _UNIX_PATH_MAX:
        raise ConfigError(
            str(source),
            _key_line(source, "state"),
            "state",
            f"the proxy's API socket there would be {len(socket_path)} bytes long: a Unix "
            f"socket's path is at most {_UNIX_PATH_MAX}",
            "choose a shorter folder, e.g. the default /var/lib/ros2-params-course.",
        )


def _check_before_start(settings: HubSettings, source: Path) -> None:
    """Refuse before anything is built or started: root, names, port, state, npm, Python."""
    if os.geteuid() != 0:
        raise CourseError(
            "A class hub runs each learner's server as their own Unix account: it needs root.",
            hint="run it as root: `sudo make hub`.",
        )
    refuse_system_accounts(settings, source)
    _check_port(settings, source)
    _check_state(settings, source)
    problem = missing_npm()
    if problem is not None and not proxy_command(Path(settings.environment)).exists():
        raise problem
    check_world_executable(Path(settings.python))


def _wall_sockets(port: int) -> tuple[bool, str]:
    """Say in one line whether learners get a network of their own; return (on, folder).

    With the wall, each learner's server socket lives in `<folder>/<name>/` (0700, theirs):
    the folder itself lets anyone through (0711) but lists nothing.
    """
    problem = "turned off by COURSE_HUB_NO_WALL" if os.environ.get(NO_WALL_ENV) else wall_problem()
    if problem is not None:
        print(
            f"The domain wall is off: this host gives no learner a network of their own "
            f"({problem}); another account that sets a learner's ROS_DOMAIN_ID reaches their "
            "nodes, and their lab's ports answer every account (book/guides/"
            "class-on-jupyterhub.md: What it does not protect against)."
        )
        return False, ""
    run = Path("/run") if Path("/run").is_dir() else Path(tempfile.gettempdir())
    folder = run / f"{WALL_PREFIX}{port}"  # one hub on a port at a time
    remove_tree(folder)  # the last start's, with its learners' folders (any depth)
    forget_stale_wall_folders(run)
    # made whole under another name, then renamed: a folder of that name always has its owner
    making = Path(tempfile.mkdtemp(prefix=f".{WALL_PREFIX}{port}-", dir=run))
    (making / WALL_OWNER).write_text(f"{owner_tag()} {pid_namespace()}\n", encoding="utf-8")
    making.chmod(0o711)
    making.rename(folder)
    print("The domain wall is on: each learner's lab runs in a network of its own.")
    return True, str(folder)


def forget_stale_wall_folders(run: Path) -> list[Path]:
    """Remove the learners' socket folders of hubs that are gone (killed: none stopped them);
    return them. A folder whose hub still runs, or ran in another PID namespace, is kept."""
    removed = []
    for folder in run.glob(f"{WALL_PREFIX}*"):
        if not folder.name.removeprefix(WALL_PREFIX).isdigit() or folder.is_symlink():
            continue
        try:
            tag, _, namespace = (folder / WALL_OWNER).read_text(encoding="utf-8").partition(" ")
        except OSError:
            tag, namespace = "", ""  # made before hubs wrote their owner: that hub is long gone
        if tag and owner_alive(tag, namespace.strip()):
            continue
        remove_tree(folder)
        removed.append(folder)
    return removed


def _plan(
    settings: HubSettings,
    state: Path,
    course: Path,
    proxy: Path,
    progress: socket.socket,
    *,
    api: socket.socket | None = None,
) -> HubPlan:
    """Return the hub's plan; the progress service's port is `progress`'s and JupyterHub's
    API port `api`'s, bound already (no `api`: a plan to look at, with none)."""
    admin_password = None
    if settings.authenticator == "shared-password":
        admin_password = secrets.token_urlsafe(32)
        (state / "admin-password.txt").write_text(admin_password + "\n", encoding="utf-8")
    wall, sockets = _wall_sockets(settings.port)
    return HubPlan(
        wall=wall,
        sockets=sockets,
        ip=settings.ip,
        port=settings.port,
        hub_port=api.getsockname()[1] if api is not None else 0,
        progress_port=progress.getsockname()[1],
        progress_token=secrets.token_hex(32),
        authenticator=settings.authenticator,
        learners=settings.learners,
        admins=settings.admins,
        state=str(state),
        course=str(course),
        proxy_command=str(proxy),
        idle_minutes=settings.idle_minutes,
        shared_password=settings.shared_password,
        admin_password=admin_password,
    )


def _keep_progress(plan: HubPlan, listener: socket.socket) -> KeptService:
    """Start the progress service on `listener`, as its own unprivileged account, from the
    learners' environment (readable by every account), its records in a folder of its own;
    start it again on the same socket whenever it dies (the caller holds `listener`)."""
    account = ensure_system_account(SERVICE_ACCOUNT)
    db = records_folder(Path(plan.state), account) / "progress.sqlite"
    environment = service_environment(plan.progress_port, plan.progress_token, plan.hub_api_url)
    return KeptService(
        lambda: start_service(plan.learner_python, db, listener, environment, account),
        "The progress service",
        log=lambda line: print(line, flush=True),
    )


def _wait_ready(hub: subprocess.Popen[bytes], url: str) -> None:
    deadline = time.monotonic() + READY_TIMEOUT_S
    while time.monotonic() < deadline:
        if hub.poll() is not None:
            raise CourseError(
                f"JupyterHub stopped while starting (exit {hub.returncode}); its log is above.",
                hint="fix what the log names, then `make hub` again.",
            )
        with (
            contextlib.suppress(urllib.error.URLError, OSError),
            urllib.request.urlopen(f"{url}hub/health", timeout=2),
        ):
            return
        time.sleep(0.3)
    raise CourseError(f"JupyterHub did not answer on {url} within {READY_TIMEOUT_S:.0f} s.")


def _stop(hub: subprocess.Popen[bytes]) -> int:
    if hub.poll() is None:
        send(hub.pid, signal.SIGTERM, reason="the class hub stops (it stops every server)")
        try:
            hub.wait(STOP_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            send(hub.pid, signal.SIGKILL, reason=f"the hub did not stop in {STOP_TIMEOUT_S:.0f} s")
            hub.wait()
    return hub.returncode or 0


def _prepare(settings: HubSettings) -> tuple[Path, Path, Path]:
    """Make the state folder, the learners' environment, the proxy and the accounts; return
    the state folder, the learners' course and the proxy's command."""
    state = Path(settings.state)
    state.mkdir(mode=0o700, parents=True, exist_ok=True)
    state.chmod(0o700)
    course = build_environment(Path(settings.environment), Path(settings.python))
    proxy = install_proxy(Path(settings.environment))
    for removal in remove_orphaned_folders():  # before an account made now takes their uid
        print(removal.line())
    accounts, passwords = ensure_accounts(
        settings.users, state, with_password=settings.authenticator == "pam"
    )
    for account in accounts:
        if account.created:
            print(f"Created the Unix account {account.name!r}.")
    if passwords:
        print(f"Their initial passwords are in {passwords} (root only): hand them out.")
    note = forget_stale_proxy(state, proxy)
    if note:
        print(note)
    if not (state / "proxy.pid").exists():  # a killed proxy's socket: its start would fail
        (state / PROXY_SOCKET).unlink(missing_ok=True)
    return state, course, proxy


def _open_gate(settings: HubSettings, plan: HubPlan, ports: list[socket.socket]) -> Gate:
    """Serve the hub's TCP `ports` (public, API, progress), held here, as doors to its Unix
    sockets (root's alone), each account's connections counted (guard/gate.py)."""
    state = Path(plan.state)
    names = (f"The hub's port {plan.port}", f"JupyterHub's API port {plan.hub_port}",
             f"The progress service's port {plan.progress_port}")  # fmt: skip
    sockets = (PROXY_SOCKET, HUB_SOCKET, PROGRESS_SOCKET)
    doors = [Door(p, str(state / s), n) for p, s, n in zip(ports, sockets, names, strict=True)]
    gate = Gate(doors, per_peer=settings.connections_per_account, log=_say)
    gate.start()
    return gate


def _say(line: str) -> None:
    print(line, flush=True)


def run_hub(config: Path = HUB_YAML) -> int:
    """Start the class hub described by `config`; stop it (and every server) on Ctrl-C."""
    settings = load_hub_settings(config)
    _check_before_start(settings, config)
    open_files_limit()  # as many as the host allows, for the gate, JupyterHub and its proxy
    state, course, proxy = _prepare(settings)
    # held until the hub has stopped: no port of the hub is ever free for another account
    with (
        _hold_port(settings, config) as public,
        socket.create_server(("127.0.0.1", 0), backlog=BACKLOG) as api,
        socket.create_server(("127.0.0.1", 0), backlog=BACKLOG) as progress,
        unix_listener(str(state / PROGRESS_SOCKET)) as behind,
    ):
        plan_data = _plan(settings, state, course, proxy, progress, api=api)
        plan = write_plan(plan_data, state / "plan.json")
        gate = _open_gate(settings, plan_data, [public, api, progress])
        service = _keep_progress(plan_data, behind)
        try:
            return _run_jupyterhub(settings, plan)
        finally:
            service.stop()
            gate.stop()
            if plan_data.sockets:  # every server has stopped: their socket folders go too
                remove_tree(plan_data.sockets)


def _run_jupyterhub(settings: HubSettings, plan: Path) -> int:
    """Run JupyterHub with `plan` until it ends or Ctrl-C; return its exit status."""
    env = {**os.environ, PLAN_ENV: str(plan)}
    signal.signal(signal.SIGTERM, signal.default_int_handler)
    hub = subprocess.Popen(
        [sys.executable, "-m", "jupyterhub", "-f", str(CONFIG_FILE)],
        cwd=plan.parent, env=env, preexec_fn=tied_preexec(),
    )  # fmt: skip
    host = "127.0.0.1" if settings.ip in ("0.0.0.0", "::") else settings.ip
    url = f"http://{host}:{settings.port}/"
    try:
        _wait_ready(hub, url)
        print(f"The class hub is up: {url} (sign in as a learner, or as an admin).")
        print(f"Progress of the class (admins only): {url}services/course-progress/")
        print("Ctrl-C stops the hub and every learner's server.")
        return hub.wait() or 0
    except KeyboardInterrupt:
        return _stop(hub)
    finally:
        _stop(hub)
