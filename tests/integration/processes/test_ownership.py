"""Which processes are the course's: spawned children, leftovers, socket holders and labs.

Processes that merely inherited the course's environment (a lab's terminals and what the
learner runs in them) are never the course's. These tests only classify (nothing is stopped),
so they are safe next to other sessions; tests/faults/test_make_stop.py stops for real.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
from collections.abc import Iterator

import pytest
from leftovers import judge_leftover
from suite_env import independent_env

from course_lib.core.host.procfs import pid_namespace
from course_lib.core.paths import runtime_dir
from course_lib.core.waiting import wait_until
from course_lib.processes.children import ChildProcess, spawn
from course_lib.processes.orphans import (
    NAME_ENV,
    OWNER_ENV,
    OWNER_NS_ENV,
    SPAWNED_ENV,
    command_tag,
    owner_tag,
    reap_orphans,
)
from course_lib.processes.ownership import course_processes, protected_pids, read_process

SLEEP = [sys.executable, "-c", "import time; print('up', flush=True); time.sleep(120)"]


def reasons() -> dict[int, str]:
    return {p.pid: p.reason for p in course_processes()}


def start_sleeper(
    started: list[subprocess.Popen], env: dict[str, str] | None = None
) -> subprocess.Popen[str]:
    """Start SLEEP; return it once it runs its code. Judged sooner, a process can be mid-exec
    (the ROS wheels' bootstrapper re-executes Python at start), with no command line or
    environment to read: a suite run found no "leftover" where one was, and a "not the
    course's" judged then would pass without proving anything."""
    proc = subprocess.Popen(SLEEP, env=env, stdout=subprocess.PIPE, text=True)
    started.append(proc)
    assert proc.stdout is not None and proc.stdout.readline() == "up\n"
    return proc


def spawn_sleeper(name: str) -> ChildProcess:
    """Spawn SLEEP as the course does; return it once it runs its code (see start_sleeper)."""
    child = spawn(SLEEP, name=name)
    assert child.wait_for_line("^up$", 30) is not None, child.text()
    return child


@pytest.fixture
def started() -> Iterator[list[subprocess.Popen]]:
    procs: list[subprocess.Popen] = []
    yield procs
    for proc in procs:
        if proc.poll() is None:
            with contextlib.suppress(ProcessLookupError):
                if os.getpgid(proc.pid) == proc.pid:  # a group of its own: what it started too
                    os.killpg(proc.pid, signal.SIGKILL)
            proc.kill()
        proc.communicate()


def test_a_spawned_child_is_the_courses_and_named() -> None:
    child = spawn_sleeper("my-node")
    try:
        found = {p.pid: p for p in course_processes()}
        assert found[child.pid].reason == "child"
        assert found[child.pid].name == "my-node"
    finally:
        child.stop(timeout=1.0)


def test_an_inherited_owner_tag_is_not_the_courses(started) -> None:
    # A shell started as a lab starts JupyterLab (a tagged child of this process), and a
    # program it runs, as the learner's editor in a terminal: same tag, but not our child.
    shell = subprocess.Popen(
        ["sh", "-c", f"{' '.join(SLEEP[:2])} 'import time; time.sleep(120)'; true"],
        env={**independent_env(), OWNER_ENV: owner_tag(), NAME_ENV: "jupyterlab"},
        start_new_session=True,  # the editor goes with it at the end (it outlived the test)
    )
    started.append(shell)
    assert wait_until(lambda: any(read_process(p) for p in _children(shell.pid)), 10.0)
    editor = _children(shell.pid)[0]
    assert process_env(editor)[OWNER_ENV] == owner_tag()  # a copied, live owner tag
    found = reasons()
    assert found.get(shell.pid) == "child"
    assert editor not in found


def test_a_copied_tag_of_a_live_process_is_not_the_courses(started) -> None:
    live_owner = start_sleeper(started)
    copied = start_sleeper(started, {**independent_env(), OWNER_ENV: owner_tag(live_owner.pid)})
    assert copied.pid not in reasons()


def test_a_dead_owners_process_is_a_leftover(started) -> None:
    owner = subprocess.Popen([sys.executable, "-c", "pass"])
    tag = owner_tag(owner.pid)
    owner.wait()
    # as the course's spawn starts it: its command recorded (a program that only inherited the
    # owner tag, one the learner started from a lab terminal, is never a leftover)
    env = {**independent_env(), OWNER_ENV: tag}
    learners = start_sleeper(started, env)
    found: dict[int, str] = {}

    def start() -> subprocess.Popen[str]:
        leftover = subprocess.Popen(
            SLEEP, env={**env, SPAWNED_ENV: command_tag(SLEEP)}, stdout=subprocess.PIPE, text=True
        )
        started.append(leftover)
        return leftover

    def judge(leftover: subprocess.Popen[str]) -> bool:
        found.clear()
        found.update(reasons())
        return found.get(leftover.pid) == "leftover"

    assert judge_leftover(start, judge)  # other sessions may reap it first: see leftovers.py
    assert learners.pid not in found


def test_a_socket_in_the_runtime_folder_makes_its_holder_the_courses(started) -> None:
    path = runtime_dir() / f"test-{os.getpid()}.sock"
    holder = subprocess.Popen(
        [
            sys.executable,
            "-c",
            "import socket, sys, time; s = socket.socket(socket.AF_UNIX);"
            f"s.bind({str(path)!r}); s.listen(); print('up', flush=True); time.sleep(120)",
        ],
        env=independent_env(),
        stdout=subprocess.PIPE,
        text=True,
    )
    started.append(holder)
    try:
        assert holder.stdout.readline() == "up\n"
        assert reasons().get(holder.pid) == "socket"
    finally:
        path.unlink(missing_ok=True)


def test_a_lab_marker_names_a_lab_only_if_it_is_one(started) -> None:
    lab = subprocess.Popen([*SLEEP[:2], "import course_lib, time; time.sleep(120)"])
    stranger = subprocess.Popen(["sleep", "120"])  # a pid a killed lab's marker may name
    started += [lab, stranger]
    markers = [runtime_dir() / f"lab-{p.pid}.domain" for p in (lab, stranger)]
    try:
        for marker in markers:
            marker.write_text("1")
        found = {p.pid: p for p in course_processes()}
        assert found[lab.pid].reason == "lab" and found[lab.pid].name == "lab"
        assert stranger.pid not in found
    finally:
        for marker in markers:
            marker.unlink(missing_ok=True)


def test_inside_a_lab_its_jupyterlab_is_kept(monkeypatch: pytest.MonkeyPatch) -> None:
    # This process plays the lab; its children: JupyterLab (kept) and a simulation (not kept).
    jupyterlab = spawn_sleeper("jupyterlab")
    simulation = spawn_sleeper("simulation")
    try:
        table = {p: read_process(p) for p in (os.getpid(), jupyterlab.pid, simulation.pid)}
        monkeypatch.setenv("COURSE_LAB", "1")
        monkeypatch.setenv(OWNER_ENV, owner_tag())
        kept = protected_pids(table)  # type: ignore[arg-type]
        assert jupyterlab.pid in kept and simulation.pid not in kept
        monkeypatch.delenv("COURSE_LAB")
        assert jupyterlab.pid not in protected_pids(table)  # type: ignore[arg-type]
    finally:
        jupyterlab.stop(timeout=1.0)
        simulation.stop(timeout=1.0)


def _children(pid: int) -> list[int]:
    found = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            info = read_process(int(entry))
            if info is not None and info.ppid == pid:
                found.append(info.pid)
    return found


def process_env(pid: int) -> dict[str, str]:
    info = read_process(pid)
    assert info is not None
    return info.env


def test_reaping_spares_a_copied_tag_of_a_live_process(started) -> None:
    live_owner = start_sleeper(started)
    copied = start_sleeper(started, {**independent_env(), OWNER_ENV: owner_tag(live_owner.pid)})
    assert copied.pid not in reap_orphans()
    assert copied.poll() is None


def test_a_tag_from_another_pid_namespace_is_never_judged_here(started) -> None:
    # pids of a container or `unshare --pid` mean other processes here: never reap by them
    owner = subprocess.Popen([sys.executable, "-c", "pass"])
    tag = owner_tag(owner.pid)
    owner.wait()
    env = {**independent_env(), OWNER_ENV: tag, SPAWNED_ENV: command_tag(SLEEP)}
    elsewhere = start_sleeper(started, {**env, OWNER_NS_ENV: "1"})
    here = start_sleeper(started, {**env, OWNER_NS_ENV: pid_namespace()})
    found = reasons()
    assert elsewhere.pid not in found and found.get(here.pid) == "leftover"
    assert elsewhere.pid not in reap_orphans()


def test_a_leftover_with_a_garbled_owner_tag_is_reaped_without_an_error(started) -> None:
    # A tag that names no pid ("x:1", edited by hand or cut short) counts as a gone owner;
    # reaping, which every session does as it starts, must not fail on it.
    env = {**independent_env(), OWNER_ENV: "x:1", SPAWNED_ENV: command_tag(SLEEP)}

    def start() -> subprocess.Popen[str]:
        leftover = subprocess.Popen(SLEEP, env=env, stdout=subprocess.PIPE, text=True)
        started.append(leftover)
        return leftover

    def judge(leftover: subprocess.Popen[str]) -> bool:
        return leftover.pid in reap_orphans() and leftover.wait(timeout=2) == -signal.SIGKILL

    assert judge_leftover(start, judge)  # other sessions may reap it first: see leftovers.py
