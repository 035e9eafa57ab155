"""A flood of idle connections from another account leaves the class hub a way in (real hub,
real accounts, issue 65: "no way in").

Two processes of a plain account of the host held about 20,000 idle connections to the hub's
own port: JupyterHub ran out of file descriptors, wrote 710k "Too many open files" lines in a
minute, and a learner could not sign in. With the common soft limit of 1024, which the hub
starts with here (its hard limit is the host's), about 1,000 do. The account here opens
thousands to every TCP port of the hub (its public port, JupyterHub's API, the progress
service, any other its processes listen on) and holds them while a learner signs in.
"""

from __future__ import annotations

import json
import os
import pwd
import resource
import subprocess
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from class_hub import ClassHub, remove_account
from hub_accounts import sign_in

from course_lib.hub.guard.gate import FIRST_BYTES_S

pytestmark = [pytest.mark.slow, pytest.mark.learners_env]

VICTIM, ADMIN, INTRUDER = "r2cf-vic", "r2cf-adm", "r2cf-eve"
HUB_FILE_LIMIT = 1024  # a common soft limit of open files: the hub starts with it here
PER_PORT = 700  # connections each of the intruder's two processes opens to each port
ACCOUNT_LIMIT = 200  # the hub's default connections_per_account (config/hub.yaml)
SIGN_IN_S = 120.0
LOG_LINES_MAX = 500  # what the hub may say during the whole attack
# The intruder's program, plain Python as that account: open `per_port` connections to each
# port and send nothing; a port whose queue is full (1 s without an answer, 5 times) is left
# (what is left counts as unanswered). Say what is open a moment later, hold it until told,
# say again.
_FLOOD = r"""
import json, resource, select, socket, sys, time
ports, per_port = [int(p) for p in sys.argv[1].split(",")], int(sys.argv[2])
resource.setrlimit(resource.RLIMIT_NOFILE, (resource.getrlimit(resource.RLIMIT_NOFILE)[1],) * 2)
held = {p: [] for p in ports}
refused, unanswered = dict.fromkeys(ports, 0), dict.fromkeys(ports, 0)
for _ in range(per_port):
    for port in ports:
        if unanswered[port] >= 5:
            unanswered[port] += 1
            continue
        s = socket.socket()
        s.settimeout(1.0)
        try:
            s.connect(("127.0.0.1", port))
            held[port].append(s)
        except TimeoutError:
            unanswered[port] += 1
            s.close()
        except OSError:
            refused[port] += 1
            s.close()

def report():
    poll = select.poll()
    by_fd = {}
    for port, sockets in held.items():
        for s in sockets:
            poll.register(s, select.POLLIN)
            by_fd[s.fileno()] = (port, s)
    closed = dict.fromkeys(ports, 0)
    for fd, _ in poll.poll(0):
        port, s = by_fd[fd]
        try:
            if s.recv(1, socket.MSG_PEEK) == b"":
                closed[port] += 1
        except OSError:  # reset
            closed[port] += 1
    return {p: {"open": len(held[p]) - closed[p], "closed": closed[p],
                "refused": refused[p], "unanswered": unanswered[p]} for p in ports}

time.sleep(3.0)  # what the hub closes at once is closed by now
print(json.dumps(report()), flush=True)
sys.stdin.readline()
print(json.dumps(report()), flush=True)
"""


def _descendants(root: int) -> list[int]:
    """Return `root` and every process under it."""
    children: dict[int, list[int]] = {}
    for entry in Path("/proc").iterdir():
        try:
            if entry.name.isdigit():
                ppid = int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
                children.setdefault(ppid, []).append(int(entry.name))
        except OSError:
            continue
    found, todo = [], [root]
    while todo:
        pid = todo.pop()
        found.append(pid)
        todo.extend(children.get(pid, []))
    return found


def _hub_tcp_ports(hub: ClassHub) -> set[int]:
    """Return every TCP port of the hub on this host: its public port, JupyterHub's own and
    the progress service's (from its plan), and every one that a root process of the hub's
    (the launcher, JupyterHub, the proxy) listens on."""
    plan = json.loads((hub.state / "plan.json").read_text())
    ports = {hub.port, plan["hub_port"], plan["progress_port"]}
    inodes = set()
    for pid in _descendants(hub.process.pid):
        try:
            if Path(f"/proc/{pid}").stat().st_uid != 0:
                continue
            links = [os.readlink(fd) for fd in Path(f"/proc/{pid}/fd").iterdir()]
        except OSError:
            continue
        inodes |= {link[8:-1] for link in links if link.startswith("socket:[")}
    for table in ("tcp", "tcp6"):
        for line in Path(f"/proc/net/{table}").read_text().splitlines()[1:]:
            fields = line.split()
            if fields[3] == "0A" and fields[9] in inodes:
                ports.add(int(fields[1].rsplit(":", 1)[1], 16))
    return ports


@pytest.fixture(scope="module")
def class_hub(tmp_path_factory: pytest.TempPathFactory) -> Iterator[ClassHub]:
    if os.geteuid() != 0:
        pytest.skip("a class hub creates Unix accounts: run as root (CI does)")
    folder = tmp_path_factory.mktemp("connection-flood-hub")
    remove_account(INTRUDER)
    argv = ["useradd", "--create-home", "--user-group", "--shell", "/bin/bash", INTRUDER]
    subprocess.run(argv, check=True, capture_output=True)
    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    resource.setrlimit(resource.RLIMIT_NOFILE, (HUB_FILE_LIMIT, hard))  # the hub inherits it
    try:
        started = ClassHub((VICTIM,), (ADMIN,), folder)
    finally:
        resource.setrlimit(resource.RLIMIT_NOFILE, (soft, hard))
    try:
        yield started
    finally:
        (folder / "hub.log").write_text(started.log(), encoding="utf-8")
        started.stop()  # removes the class's accounts
        remove_account(INTRUDER)


def _flood(ports: list[int]) -> subprocess.Popen[str]:
    """Start one of the intruder's processes, from the host's network."""
    account = pwd.getpwnam(INTRUDER)

    def become() -> None:
        os.setgroups([])
        os.setgid(account.pw_gid)
        os.setuid(account.pw_uid)

    return subprocess.Popen(
        ["/usr/bin/python3", "-c", _FLOOD, ",".join(map(str, ports)), str(PER_PORT)],
        preexec_fn=become, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
        env={"PATH": os.defpath}, cwd=account.pw_dir,
    )  # fmt: skip


def _sum(reports: list[dict[str, dict[str, int]]], key: str) -> int:
    return sum(counts[key] for report in reports for counts in report.values())


def test_a_flood_of_idle_connections_leaves_the_hub_a_way_in(class_hub: ClassHub) -> None:
    ports = sorted(_hub_tcp_ports(class_hub))
    lines = [0]
    class_hub.process.add_listener(lambda _: lines.__setitem__(0, lines[0] + 1))
    began = time.monotonic()
    floods = [_flood(ports), _flood(ports)]
    try:
        opened = [json.loads(flood.stdout.readline()) for flood in floods]  # type: ignore[union-attr]
        opened_s = time.monotonic() - began
        signing = time.monotonic()
        failure = ""
        try:
            sign_in(class_hub, VICTIM, timeout=SIGN_IN_S)
        except Exception as error:  # any way the sign-in fails: said below, with the numbers
            failure = f"{type(error).__name__}: {str(error)[:300]}"
        signed_s = time.monotonic() - signing
        time.sleep(max(0.0, began + opened_s + FIRST_BYTES_S + 5.0 - time.monotonic()))
        for flood in floods:
            flood.stdin.write("stop\n")  # type: ignore[union-attr]
            flood.stdin.flush()  # type: ignore[union-attr]
        held = [json.loads(flood.stdout.readline()) for flood in floods]  # type: ignore[union-attr]
    finally:
        for flood in floods:
            flood.kill()
            flood.communicate()  # and closes its pipes
    attempts = len(floods) * PER_PORT * len(ports)
    kept, shut = _sum(opened, "open"), _sum(opened, "closed") + _sum(opened, "refused")
    said = (
        f"ports {ports}: the intruder tried {attempts} connections in {opened_s:.0f} s; "
        f"{kept} stayed open, {shut} were refused or closed at once, "
        f"{_sum(opened, 'unanswered')} found a full queue; the sign-in took {signed_s:.0f} s"
        f"{', and failed: ' + failure if failure else ''}; {_sum(held, 'open')} were still "
        f"open {FIRST_BYTES_S + 5:.0f} s later; the hub wrote {lines[0]} lines meanwhile"
    )
    print(said, json.dumps(opened), sep="\n")
    assert not failure, said
    assert lines[0] <= LOG_LINES_MAX, f"{said}:\n{class_hub.log()[-3000:]}"
    assert kept <= ACCOUNT_LIMIT, said
    assert kept + shut + _sum(opened, "unanswered") == attempts, said  # none hangs
    assert _sum(held, "open") == 0, f"idle connections are closed after a while: {said}"
