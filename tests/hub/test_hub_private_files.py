"""What the instructor writes for the hub, and what a learner keeps in their home, stay theirs
(real hub, real accounts).

The instructor puts the demo's password in their clone's config/hub.yaml, a file git tracks,
closes that file to others (0600) and starts the hub from the clone. One learner's account was
there before the hub, with Debian's 0755 home and an answer of an earlier class in my_files/.
Another learner of the class, and an account of the host that is in no class, then look for
the password in every file of the hub they can open, and read the first learner's answer.
"""

from __future__ import annotations

import json
import os
import pwd
import secrets
import shutil
import subprocess
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest
from class_hub import ClassHub, remove_account
from hub_accounts import as_account, sign_in

from course_lib.core.paths import REPO_ROOT
from course_lib.hub.launcher import WALL_PREFIX
from course_lib.hub.provision.environment import source_files

pytestmark = [pytest.mark.slow, pytest.mark.learners_env]

OLD, NEW, ADMIN, OUTSIDER = "r2pf-old", "r2pf-new", "r2pf-adm", "r2pf-out"
ANSWER = "ros2-params-course/notebooks/my_files/answer.txt"  # in OLD's home
DEBIAN_PYTHON = "/usr/bin/python3"  # every account may run it (the course's may be root's)

# Run as an account: every regular file under the folders named, that account's own folders
# and every process's command line and environment it may open; the password comes on stdin.
_SEARCH = r"""
import json, os, stat, sys, tempfile
secret = sys.stdin.read().strip().encode()
uid = os.getuid()
course_tmp = os.path.join(tempfile.gettempdir(), f"ros2-course-{uid}")  # the runtime folder
roots = [*sys.argv[1:], os.path.expanduser("~"), course_tmp, f"/run/user/{uid}", "/dev/shm"]
found, read = [], []

def look(path):
    try:
        with open(path, "rb") as opened:
            data = opened.read(4 << 20)
    except OSError:
        return
    read.append(path)
    if secret in data:
        found.append(path)

for root in roots:
    for folder, _, files in os.walk(root):
        for name in files:
            path = os.path.join(folder, name)
            try:
                regular = stat.S_ISREG(os.stat(path).st_mode)
            except OSError:
                continue
            if regular:
                look(path)
for pid in os.listdir("/proc"):
    if pid.isdigit() and int(pid) != os.getpid():
        look(f"/proc/{pid}/cmdline")
        look(f"/proc/{pid}/environ")
print(json.dumps({"found": found, "read": read}))
"""


def _clone(folder: Path) -> Path:
    """Return a clone of the course in `folder`: the files git tracks here (as they are now),
    tracked there too; config/hub.yaml, the course's own, closed to other accounts."""
    clone = folder / "course"
    for relative in {*source_files(REPO_ROOT), "config/hub.yaml"}:
        (clone / relative).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(REPO_ROOT / relative, clone / relative)
    (clone / "config" / "hub.yaml").chmod(0o600)
    for argv in (["init", "-q"], ["add", "-A"]):
        subprocess.run(["git", *argv], cwd=clone, check=True, capture_output=True)
    return clone


def _make_old_learner() -> bool:
    """Make OLD's account as an administrator did before the hub (Debian's 0755 home), with an
    answer in their my_files/, and the outsider's; return whether the outsider reads it."""
    for name in (OLD, OUTSIDER):
        remove_account(name)
        argv = ["useradd", "--create-home", "--user-group", "--shell", "/bin/bash", name]
        subprocess.run(argv, check=True, capture_output=True)
    home = Path(pwd.getpwnam(OLD).pw_dir)
    home.chmod(0o755)
    write = f"umask 022; mkdir -p {Path(ANSWER).parent} && echo 'v = 0.26' > {ANSWER}"
    done = as_account(OLD, ["/bin/sh", "-c", write], {})
    assert done.returncode == 0, done.stderr
    return as_account(OUTSIDER, ["cat", str(home / ANSWER)], {}).returncode == 0


@pytest.fixture(scope="module")
def password() -> str:
    return secrets.token_urlsafe(18)


@pytest.fixture(scope="module")
def before() -> dict[str, bool]:
    """What the outsider could do before the hub started."""
    return {}


@pytest.fixture(scope="module")
def hub(
    tmp_path_factory: pytest.TempPathFactory, password: str, before: dict[str, bool]
) -> Iterator[ClassHub]:
    if os.geteuid() != 0:
        pytest.skip("a class hub creates Unix accounts: run as root (CI does)")
    folder = tmp_path_factory.mktemp("private-files-hub")
    clone = _clone(folder)
    started = ClassHub(
        (OLD, NEW), (ADMIN,), folder,
        course=clone, config=clone / "config" / "hub.yaml",
        settings=f"authenticator: shared-password\nshared_password: {password}\n",
        before_start=lambda: before.update(answer_read=_make_old_learner()),
    )  # fmt: skip
    started.passwords = {OLD: password, NEW: password}
    try:
        yield started
    finally:
        (folder / "hub.log").write_text(started.log(), encoding="utf-8")
        started.stop()  # removes the class's accounts
        remove_account(OUTSIDER)


def _hub_folders(hub: ClassHub) -> list[str]:
    """Return the hub's folders: the learners' environment, the servers' sockets, its state
    and the progress records."""
    run = Path("/run") if Path("/run").is_dir() else Path(tempfile.gettempdir())
    sockets = run / f"{WALL_PREFIX}{hub.port}"
    progress = hub.state.parent / f"{hub.state.name}-progress"
    return [str(p) for p in (hub.environment, sockets, hub.state, progress)]


def test_no_account_reads_the_demo_password_in_the_hubs_files(
    hub: ClassHub, password: str
) -> None:
    """config/hub.yaml was copied into the learners' environment and opened to all (0644),
    though the instructor's was 0600: any account could sign in as any learner."""
    sign_in(hub, NEW)  # their server runs: its sockets and runtime folders are there too
    course_yaml = str(hub.environment / "course" / "config" / "course.yaml")
    for name in (NEW, OUTSIDER):
        done = as_account(
            name, [DEBIAN_PYTHON, "-c", _SEARCH, *_hub_folders(hub)], {}, 600.0, stdin=password
        )
        assert done.returncode == 0, done.stderr[-2000:]
        result = json.loads(done.stdout)
        assert result["found"] == [], f"{name} read the demo's password in {result['found']}"
        assert course_yaml in result["read"], f"{name} searched nothing of the environment"
    assert not (hub.environment / "course" / "config" / "hub.yaml").exists()
    # what a lab reads of config/ is all there: `make doctor`'s check passes without hub.yaml
    python = str(hub.environment / "course" / ".venv" / "bin" / "python")
    checked = as_account(NEW, [python, "-m", "course_lib", "check-config"], {}, 120.0)
    assert checked.returncode == 0, checked.stdout + checked.stderr
    assert "course.yaml, simulation.yaml are valid" in checked.stdout, checked.stdout


def test_a_learner_account_made_before_the_hub_has_a_private_home(
    hub: ClassHub, before: dict[str, bool]
) -> None:
    """Only the accounts the hub created had a 0700 home: a learner's made before it kept
    Debian's 0755, another account read their my_files/answer.txt, and the hub said nothing."""
    home = Path(pwd.getpwnam(OLD).pw_dir)
    answer = home / ANSWER
    assert before["answer_read"], "the outsider could not read the answer even before the hub"
    for name in (OUTSIDER, NEW):
        read = as_account(name, ["cat", str(answer)], {})
        assert read.returncode != 0 and "Permission denied" in read.stderr, (name, read)
    assert home.stat().st_mode & 0o077 == 0
    assert f"Made the home of {OLD!r} private" in hub.log(), hub.log()[-4000:]
    sign_in(hub, OLD)  # their lab starts in the closed home, their answer still theirs
    assert as_account(OLD, ["cat", str(answer)], {}).stdout == "v = 0.26\n"
