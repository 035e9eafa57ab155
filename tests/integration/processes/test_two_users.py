"""Two Unix users on one host lease different domains and never see each other's nodes.

Each user is created for the test (root only, as in CI) and runs a real course session with
the system Python 3 (the course's own interpreter may live in a home other users cannot
enter) on this checkout's packages. Both start their search at the same domain id, so a
lease that other users could not see would hand both the same one.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
import uuid
from collections.abc import Iterator
from pathlib import Path

import pytest
from suite_env import TEST_ENV

from course_lib.core.paths import REPO_ROOT
from course_lib.processes.domain import lease_domain

pytestmark = [pytest.mark.ros, pytest.mark.slow]

# A learner's session: lease a domain and report it; on "go" (both hold their lease, no DDS
# socket is open yet) start a session in it with a named node, and list every node it
# discovers for a while.
LEARNER = """
import json, sys, time
import rclpy
from course_lib.processes.domain import lease_domain
from course_lib.session.session import Session
name, start = sys.argv[1], int(sys.argv[2])
lease = lease_domain(start=start)
print(json.dumps({"domain": lease.domain_id}), flush=True)
sys.stdin.readline()
session = Session(domain_id=lease.domain_id)
node = rclpy.create_node(name, context=session.context)
seen, deadline = set(), time.monotonic() + 5.0
while time.monotonic() < deadline:
    seen |= {n for n in session.node.get_node_names() if not n.startswith("_")}
    time.sleep(0.1)
print(json.dumps({"seen": sorted(seen)}), flush=True)
node.destroy_node()
session.close()
"""
# The control: a plain rclpy node in the domain of ROS_DOMAIN_ID, same report.
PLAIN = """
import json, sys, time
import rclpy
rclpy.init()
node = rclpy.create_node(sys.argv[1])
print(json.dumps({"domain": node.context.get_domain_id()}), flush=True)
sys.stdin.readline()
seen, deadline = set(), time.monotonic() + 5.0
while time.monotonic() < deadline:
    seen |= set(node.get_node_names())
    time.sleep(0.1)
print(json.dumps({"seen": sorted(seen)}), flush=True)
"""


def _system_python() -> str:
    python = shutil.which("python3", path=os.defpath)
    if python is None:
        pytest.skip("no system python3 for the other users")
    version = subprocess.run(
        [python, "-c", "import sys; print(sys.version_info[:2])"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()
    if version != str(sys.version_info[:2]):
        pytest.skip(f"system python3 is {version}: it cannot load this venv's packages")
    return python


@pytest.fixture(scope="module")
def users() -> Iterator[list[tuple[str, int, Path]]]:
    """Create two Unix users with a private temporary folder each; remove them after."""
    if os.geteuid() != 0 or shutil.which("useradd") is None:
        pytest.skip("creating Unix users needs root and useradd (CI runs as root)")
    made = []
    try:
        for _ in range(2):
            name = f"rc{uuid.uuid4().hex[:8]}"
            subprocess.run(
                ["useradd", "--system", "--user-group", "--no-create-home", name], check=True
            )
            uid = int(subprocess.run(["id", "-u", name], capture_output=True, check=True).stdout)
            home = Path(tempfile.mkdtemp(prefix=f"{name}-"))
            os.chown(home, uid, uid)
            made.append((name, uid, home))
        yield made
    finally:
        for name, _uid, home in made:
            shutil.rmtree(home, ignore_errors=True)
            subprocess.run(["userdel", name], check=False)


def _learner_env(home: Path, extra: dict[str, str]) -> dict[str, str]:
    site = next(p for p in sys.path if p.endswith("site-packages") and Path(p).is_dir())
    env = {
        **TEST_ENV,
        "PATH": os.defpath,
        "HOME": str(home),
        "TMPDIR": str(home),
        "ROS_LOG_DIR": str(home / "log"),
        "PYTHONPATH": os.pathsep.join([str(REPO_ROOT), site]),
        "PYTHONDONTWRITEBYTECODE": "1",
        # the venv's ROS libraries, found as its .pth bootstrapper finds them
        "LD_LIBRARY_PATH": os.environ.get("LD_LIBRARY_PATH", ""),
        "_ROS_WHEELS_BOOTSTRAP_COMPLETE": "1",
    }
    return {**env, **extra}


def _run_both(
    users: list[tuple[str, int, Path]], script: str, extra: dict[str, str]
) -> list[dict]:
    """Start both users' sessions at once; return what each leased and saw."""
    python = _system_python()
    probe = lease_domain({})  # a free domain now: both users start their search there
    start = probe.domain_id
    probe.release()
    learners = [
        subprocess.Popen(
            [python, "-c", script, f"node_of_{name}", str(start)],
            env=_learner_env(home, extra),
            user=uid,
            group=uid,
            extra_groups=[],
            cwd=home,
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for name, uid, home in users
    ]
    try:
        reports = []
        for learner in learners:
            line = learner.stdout.readline()
            assert line, learner.communicate(timeout=30)[1][-3000:]
            reports.append(json.loads(line))
        for learner in learners:
            learner.stdin.write("go\n")
            learner.stdin.flush()
        for learner, report in zip(learners, reports, strict=True):
            out, err = learner.communicate(timeout=60)
            assert learner.returncode == 0, err[-3000:]
            report.update(json.loads(out.splitlines()[-1]))
        return reports
    finally:
        for learner in learners:
            if learner.poll() is None:
                learner.kill()
                learner.communicate()


def test_two_users_get_different_domains_and_never_meet(users) -> None:
    first, second = _run_both(users, LEARNER, {})
    assert first["domain"] != second["domain"]
    (a, _, _), (b, _, _) = users
    assert first["seen"] == [f"node_of_{a}"], first
    assert second["seen"] == [f"node_of_{b}"], second


def test_control_users_in_one_domain_do_see_each_other(users) -> None:
    # The check above can see another user's node: in one domain, with discovery over UDP
    # (the shared-memory transport does not cross users), the two users' nodes meet.
    # leased, never read from os.environ: this worker's own session exports its domain there
    # (a full run saw its `_course_client_<pid>` node here, three times of three); held for
    # the whole test, so no session leases it meanwhile
    lease = lease_domain({})
    shared = str(lease.domain_id)
    extra = {
        "ROS_DOMAIN_ID": shared,
        "ROS_AUTOMATIC_DISCOVERY_RANGE": "SUBNET",
        "FASTDDS_BUILTIN_TRANSPORTS": "UDPv4",
    }
    try:
        first, second = _run_both(users, PLAIN, extra)
    finally:
        lease.release()
    (a, _, _), (b, _, _) = users
    assert first["domain"] == second["domain"] == int(shared)
    assert first["seen"] == second["seen"] == sorted([f"node_of_{a}", f"node_of_{b}"])
