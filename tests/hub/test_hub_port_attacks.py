"""Attack tests on the class hub's own ports (real hub, real accounts, issue 65): a progress
service that dies as a crash would leaves its port to no other account and starts again on
it; the proxy's API has no port another account could take.

Before, the launcher closed its copy of the progress service's socket and nothing started
the service again: another account bound the freed port and caught a learner's server token
from their next self-check (with it, a terminal in their lab ran as them). The proxy's API
was on a port picked free, released and shown in `ps`: while the proxy was down, another
account bound it and received the proxy's auth token with the hub's next call.
"""

from __future__ import annotations

import itertools
import json
import os
import pwd
import signal
import subprocess
from collections.abc import Iterator
from pathlib import Path

import pytest
import requests
from class_hub import ClassHub, server_token
from hub_accounts import as_account, lab_terminal, sign_in
from hub_sign_in import sign_in as sign_in_form
from lab_terminal import RestTerminal

from course_lib.core.host.procfs import cmdline, pids
from course_lib.core.waiting import wait_until

pytestmark = [pytest.mark.slow, pytest.mark.learners_env]

VICTIM, INTRUDER, ADMIN = "r2pp-vic", "r2pp-eve", "r2pp-adm"
BIND_FOR_S = 8.0  # how long the intruder keeps trying to bind (a restart takes 2-5 s)
CATCH_FOR_S = 40.0  # then how long a bound port waits for a token
# The intruder's program, plain Python as that account: bind the port every way it can, then
# take what comes and answer it as the service would.
_SQUAT = r"""
import json, re, socket, sys, time
port, bind_s, catch_s = int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3])
ways = [("127.0.0.1", socket.SO_REUSEADDR), ("127.0.0.1", socket.SO_REUSEPORT),
        ("0.0.0.0", socket.SO_REUSEADDR)]
began, tries, held = time.monotonic(), 0, None
while held is None and time.monotonic() < began + bind_s:
    for host, option in ways:
        tries += 1
        s = socket.socket()
        s.setsockopt(socket.SOL_SOCKET, option, 1)
        try:
            s.bind((host, port)); s.listen(16); held = s; break
        except OSError:
            s.close()
    time.sleep(0.005)
print(json.dumps({"bound": held is not None, "tries": tries}), flush=True)
tokens, end = [], time.monotonic() + catch_s
while held is not None and not tokens and time.monotonic() < end:
    held.settimeout(0.5)
    try:
        conn, _ = held.accept()
    except OSError:
        continue
    conn.settimeout(2)
    data = b""
    try:
        while b"\r\n\r\n" not in data and (chunk := conn.recv(65536)):
            data += chunk
    except OSError:
        pass
    tokens += re.findall(r"(?i)authorization: token (\S+)", data.decode(errors="replace"))
    conn.sendall(b"HTTP/1.1 201 Created\r\nContent-Type: application/json\r\n"
                 b"Content-Length: 2\r\nConnection: close\r\n\r\n{}")
    conn.close()
print(json.dumps({"tokens": tokens}), flush=True)
"""
# What a lesson's self-check sends, from a terminal of the victim's lab (its server's env).
_SELF_CHECK = (
    'python -c "from course_lib.lessons.progress.client import report_progress; '
    "from course_lib.lessons.report import SelfCheck, check; "
    "t = report_progress(SelfCheck.of({lesson}, [check('{what}', False)])); "
    "t.join(10); print('self-check', 'done')\""
)


@pytest.fixture(scope="module")
def class_hub(tmp_path_factory: pytest.TempPathFactory) -> Iterator[ClassHub]:
    if os.geteuid() != 0:
        pytest.skip("a class hub creates Unix accounts: run as root (CI does)")
    folder = tmp_path_factory.mktemp("port-attacks-hub")
    started = ClassHub((VICTIM, INTRUDER), (ADMIN,), folder)
    try:
        yield started
    finally:
        (folder / "hub.log").write_text(started.log(), encoding="utf-8")
        started.stop()  # removes the accounts


@pytest.fixture(scope="module")
def victim_lab(class_hub: ClassHub) -> Iterator[RestTerminal]:
    sign_in(class_hub, VICTIM)
    terminal = lab_terminal(class_hub, VICTIM)
    try:
        yield terminal
    finally:
        terminal.close()


def _progress_service(class_hub: ClassHub) -> int | None:
    """Return the pid of this hub's progress service (its records are beside its state)."""
    for pid in pids():
        argv = cmdline(pid) or ()
        ours = any(arg.startswith(str(class_hub.state.parent)) for arg in argv)
        if "course_lib.hub.progress" in argv and ours:
            return pid
    return None


def _proxy(class_hub: ClassHub) -> tuple[int, tuple[str, ...]] | None:
    """Return the pid and command line of this hub's proxy (`--socket <its state>/proxy.sock`)."""
    for pid in pids():
        argv = cmdline(pid) or ()
        ours = ("--socket", str(class_hub.state / "proxy.sock")) in itertools.pairwise(argv)
        if ours and any(arg.endswith("configurable-http-proxy") for arg in argv):
            return pid, argv
    return None


def _answers(url: str, token: str = "") -> int:
    """Return the status of a GET of `url` (with `token`, if given), 0 if nothing answers."""
    headers = {"Authorization": f"token {token}"} if token else {}
    try:
        return requests.get(url, headers=headers, timeout=5).status_code
    except requests.RequestException:
        return 0


def _squatter(port: int) -> subprocess.Popen[str]:
    """Start the intruder's program on `port`, as the intruder, from the host's network."""
    account = pwd.getpwnam(INTRUDER)

    def become() -> None:
        os.setgroups([])
        os.setgid(account.pw_gid)
        os.setuid(account.pw_uid)

    return subprocess.Popen(
        ["/usr/bin/python3", "-c", _SQUAT, str(port), str(BIND_FOR_S), str(CATCH_FOR_S)],
        preexec_fn=become, stdout=subprocess.PIPE, text=True, env={"PATH": os.defpath},
        cwd=account.pw_dir,
    )  # fmt: skip


def _caught(squatter: subprocess.Popen[str]) -> list[str]:
    """Return the tokens the intruder caught (waits for their program to end)."""
    assert squatter.stdout is not None
    out, _ = squatter.communicate(timeout=CATCH_FOR_S + 30)
    return json.loads(out.strip().splitlines()[-1])["tokens"] if out.strip() else []


def _as_whom(class_hub: ClassHub, name: str, token: str) -> str:
    """Return who a terminal opened in `name`'s lab with `token` runs as (or why none)."""
    try:
        terminal = RestTerminal(f"{class_hub.url}/user/{name}", token)
    except Exception as error:  # refused: the token opens nothing
        return f"(refused: {error})"
    try:
        return terminal.run("echo who=$(id -un)", r"who=([\w-]+)")[1]
    finally:
        terminal.close()


def _records_of(class_hub: ClassHub, name: str) -> list[dict]:
    """Return `name`'s records as the admin reads them through the hub."""
    session, _ = sign_in_form(class_hub.url, ADMIN, class_hub.passwords[ADMIN])
    page = f"{class_hub.url}/services/course-progress/"
    assert session.get(page, timeout=30).status_code == 200  # the service's OAuth login
    records = session.get(f"{page}api/records", timeout=30).json()["records"]
    return [r for r in records if r["user"] == name]


def test_a_dead_progress_service_leaves_its_port_and_a_learners_token_to_nobody(
    class_hub: ClassHub, victim_lab: RestTerminal
) -> None:
    port = json.loads((class_hub.state / "plan.json").read_text())["progress_port"]
    service = _progress_service(class_hub)
    assert service is not None, "no progress service runs"
    squatter = _squatter(port)
    os.kill(service, signal.SIGKILL)  # as a crash would
    assert squatter.stdout is not None
    took = json.loads(squatter.stdout.readline())
    if not took["bound"]:  # the learner's next self-check goes once the service is back
        records = f"http://127.0.0.1:{port}/services/course-progress/api/records"
        assert wait_until(lambda: _answers(records) == 401, 60.0), class_hub.log()[-3000:]
    victim_lab.run(_SELF_CHECK.format(lesson=5, what="probe one"), r"self-check done")
    tokens = _caught(squatter)
    whom = [_as_whom(class_hub, VICTIM, token) for token in tokens]
    print(f"the intruder tried {took['tries']} binds; bound: {took['bound']}; tokens: {whom}")
    assert not took["bound"] and not tokens, (
        f"the intruder bound the dead service's port in {took['tries']} tries and caught "
        f"{len(tokens)} token(s) of a self-check; a terminal in {VICTIM}'s lab opened with "
        f"it runs as {whom}"
    )
    assert _progress_service(class_hub) not in (None, service), "started again"
    assert "The progress service stopped (killed by SIGKILL); started again" in class_hub.log()
    # the self-check sent once it was back, and one sent now, are both recorded
    victim_lab.run(_SELF_CHECK.format(lesson=6, what="probe two"), r"self-check done")
    kept = {r["lesson"]: r["failed"] for r in _records_of(class_hub, VICTIM)}
    assert kept.get(5) == "probe one" and kept.get(6) == "probe two", kept


def test_the_proxys_api_has_no_port_another_account_could_take(
    class_hub: ClassHub, victim_lab: RestTerminal
) -> None:
    before = _proxy(class_hub)
    assert before is not None, "no proxy runs"
    pid, argv = before
    api_port = argv[argv.index("--api-port") + 1] if "--api-port" in argv else None
    squatter = _squatter(int(api_port)) if api_port else None
    os.kill(pid, signal.SIGKILL)  # as a crash would: JupyterHub starts it again
    took = json.loads(squatter.stdout.readline()) if squatter and squatter.stdout else {}
    tokens = _caught(squatter) if squatter is not None else []
    assert not tokens, (
        f"the proxy's API port {api_port} (in ps) went to the intruder "
        f"({took.get('tries')} tries), who caught {len(tokens)} token(s) the hub sends the proxy"
    )
    assert api_port is None, f"the proxy's API listens on port {api_port}, shown in ps"
    back = wait_until(lambda: (p := _proxy(class_hub)) and p[0] != pid and p, 60.0)
    assert back, f"the hub did not start its proxy again:\n{class_hub.log()[-3000:]}"
    socket_path = Path(back[1][back[1].index("--api-socket") + 1])
    assert socket_path.parent == class_hub.state, socket_path
    assert class_hub.state.stat().st_mode & 0o077 == 0, "the hub's state folder is root's"
    probe = f"import socket; socket.socket(socket.AF_UNIX).connect({str(socket_path)!r})"
    tried = as_account(INTRUDER, ["/usr/bin/python3", "-c", probe], {})
    assert "PermissionError" in tried.stderr, tried.stdout + tried.stderr
    # the hub gave the new proxy its routes back: the learner's lab answers through it
    url, token = f"{class_hub.url}/user/{VICTIM}/api/status", server_token(VICTIM)
    assert wait_until(lambda: _answers(url, token) == 200, 60.0), (
        f"{VICTIM}'s lab does not answer through the restarted proxy"
    )
