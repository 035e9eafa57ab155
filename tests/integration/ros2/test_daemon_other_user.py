"""The `ros2` daemon serves its own user only, even when its socket is reachable by others.

The socket lives in the user's private runtime folder (mode 700) with mode 600; these tests
open both by mistake and show that a connection from another Unix user is still closed
unanswered (the daemon checks the peer's credentials), while the user's own is served.
Root only (it runs the other user's client as `nobody`), as in CI.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest

from course_lib.core.paths import REPO_ROOT
from course_lib.core.waiting import wait_until
from course_lib.processes.domain import lease_domain
from course_lib.ros2.command.daemon import start_daemon
from course_lib.session.session import session_env

pytestmark = [pytest.mark.ros, pytest.mark.slow]

NOBODY = 65534
# A terminal's client in plain Python: send `ros2 node list`, print every byte answered.
CLIENT = """
import json, socket, sys
sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
sock.connect(sys.argv[1])
answer = b""
try:  # connected: a refusal is a connection closed (or reset) with nothing answered
    sock.sendall(json.dumps({"argv": ["node", "list"], "cwd": "/", "width": 80}).encode() + b"\\n")
    while b'"exit"' not in answer and (chunk := sock.recv(4096)):
        answer += chunk
except (BrokenPipeError, ConnectionResetError):
    pass
print(json.dumps(answer.decode()))
"""


def _system_python() -> str:
    python = shutil.which("python3", path=os.defpath)
    if python is None:
        pytest.skip("no system python3 for the other user")
    return python


@pytest.fixture
def open_socket() -> Iterator[Path]:
    """Yield the socket of a running daemon whose folder and socket are open to everyone."""
    if os.getuid() != 0:
        pytest.skip("needs root to run a client as another user")
    base = Path(tempfile.mkdtemp(prefix="daemon-other-user-", dir=os.sep + "tmp"))
    lease = lease_domain({})
    env = {**session_env(lease.domain_id), "TMPDIR": str(base), "PYTHONPATH": str(REPO_ROOT)}
    env.pop("XDG_RUNTIME_DIR", None)
    child = start_daemon(env)
    try:
        runtime = base / f"ros2-course-{os.getuid()}"
        sock = runtime / f"ros2-daemon-{lease.domain_id}.sock"
        assert wait_until(sock.exists, 30), child.text()
        for folder in (base, runtime):
            folder.chmod(0o755)  # the mistake: anyone may reach the socket ...
        sock.chmod(0o666)  # ... and connect to it
        yield sock
    finally:
        child.stop()
        lease.release()
        shutil.rmtree(base, ignore_errors=True)


def _ask(sock: Path, *, user: int | None) -> str:
    proc = subprocess.run(
        [_system_python(), "-S", "-c", CLIENT, str(sock)],
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
        user=user,
        cwd=os.sep,
    )
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout)


def test_another_user_gets_no_answer_and_the_owner_does(open_socket: Path) -> None:
    assert _ask(open_socket, user=NOBODY) == ""
    frames = [json.loads(line) for line in _ask(open_socket, user=None).splitlines()]
    assert frames[-1] == {"exit": 0}
