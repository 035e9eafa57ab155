"""The hub's relay into a lab's network carries nothing to a host port another account holds
(a learner's token rides on what it carries): real namespaces, a real second account."""

from __future__ import annotations

import asyncio
import json
import os
import pwd
import subprocess
import sys
from collections.abc import Callable

import pytest

from course_lib.core.host.ports import free_port
from course_lib.hub.guard.wall import Relay, enter_own_network, wall_problem

pytestmark = pytest.mark.slow

# another account's program on the host: listen on the port, keep whatever comes in 5 s
_TAKER = """
import json, socket, sys, time
server = socket.socket()
server.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
server.bind(("127.0.0.1", int(sys.argv[1]))); server.listen(8); server.settimeout(0.5)
print("listening", flush=True)
got, end = b"", time.monotonic() + 5
while time.monotonic() < end and not got:
    try:
        conn, _ = server.accept()
    except OSError:
        continue
    conn.settimeout(2)
    try:
        got = conn.recv(4096)
    except OSError:
        pass
    conn.close()
print(json.dumps(got.decode(errors="replace")), flush=True)
"""
# what a kernel does inside the lab: connect to the relayed port, send its token
_KERNEL = """
import socket, sys
try:
    with socket.create_connection(("127.0.0.1", int(sys.argv[1])), timeout=5) as s:
        s.sendall(b"POST /api/records HTTP/1.1\\r\\nAuthorization: token s3cret\\r\\n\\r\\n")
        s.recv(100)
except OSError:
    pass
"""


def _as(account: pwd.struct_passwd) -> Callable[[], None]:
    def become() -> None:
        os.setgroups([])
        os.setgid(account.pw_gid)
        os.setuid(account.pw_uid)

    return become


async def _relay_one_connection(lab: int, port: int) -> list[str]:
    said: list[str] = []
    relay = Relay(lab, [port], said.append)  # the hub's (root's) relay
    await relay.start()
    try:
        kernel = await asyncio.create_subprocess_exec(
            "nsenter", f"--net=/proc/{lab}/ns/net", sys.executable, "-c", _KERNEL, str(port)
        )
        await asyncio.wait_for(kernel.wait(), 30)
    finally:
        relay.close()
    return said


def test_the_relay_sends_nothing_to_a_port_another_account_took() -> None:
    if os.geteuid() != 0:
        pytest.skip("a lab's network of its own needs root (CI runs as root)")
    if wall_problem():
        pytest.skip(f"no network namespace here: {wall_problem()}")
    port = free_port()
    taker = subprocess.Popen(
        ["/usr/bin/python3", "-c", _TAKER, str(port)], stdout=subprocess.PIPE, text=True,
        preexec_fn=_as(pwd.getpwnam("nobody")), env={"PATH": os.defpath}, cwd="/",
    )  # fmt: skip
    lab = subprocess.Popen(["sleep", "60"], preexec_fn=enter_own_network)
    try:
        assert taker.stdout is not None and taker.stdout.readline().strip() == "listening"
        said = asyncio.run(_relay_one_connection(lab.pid, port))
        got = json.loads(taker.communicate(timeout=30)[0].strip().splitlines()[-1])
    finally:
        for process in (taker, lab):
            process.kill()
            process.wait()
    assert "s3cret" not in got, f"the relay carried the lab's token to nobody's port: {got!r}"
    assert any("another account than the hub's holds that port" in line for line in said), said
