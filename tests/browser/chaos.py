"""Faults between a learner's steps (issue 62, `make chaos`): a process of the lab killed or
stopped, the page reloaded; then the learner's next step, and the lab whole again.

Each fault acts on the lab's own tree (never anything else): the simulation, a lesson's node,
the `ros2` daemon, a lesson's kernel (idle, or busy in a Run All), the Jupyter server (the
lab starts it again at its address) killed with SIGKILL; the
simulation, or every process of the lab, stopped for 10 s (SIGSTOP, then SIGCONT: a suspended
laptop); the browser page reloaded. After
it, the learner's next step may say in one line what happened (a course error, never a
traceback); the learner then does what it says (the lesson's first cell, then Run All), and
that must be clean. Within 10 s of the next step the lab is whole:
at most one world, no node name twice, as many /clock publishers as worlds, and no process of
the lab's ROS domain outside the lab.
"""

from __future__ import annotations

import os
import random
import re
import signal
import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field

import psutil
from lab_graph import _plain
from lesson_checks import PROBES, lesson_number
from terminal import Terminal
from walk import Step, Walker, seed_and_count

from course_lib.processes.orphans import OWNER_ENV, owner_tag

__all__ = ["FAULTS", "ChaosWalker", "chaos_settings"]

STOP_S = 10.0  # a suspended laptop
WORLD_FIRST = "07_move_the_robot.ipynb"
WHOLE_WITHIN_S = 10.0
KERNEL_NOTICE_S = 15.0  # JupyterLab's "The kernel ... appears to have died"
SERVER_BACK_S = 30.0  # the lab's launcher starts a killed server again

_TARGETS: dict[str, Callable[[list[str]], bool]] = {
    "the simulation": lambda argv: "course_lib.sim" in argv,
    "a lesson's node": lambda argv: any(
        a.endswith(("/param_vel", "/descriptor_vel")) for a in argv
    ),
    "the ros2 daemon": lambda argv: "course_lib.ros2.command.daemon" in argv,
    "a lesson's kernel": lambda argv: "course_lib.notebook.kernel_launcher" in argv,
    "the Jupyter server": lambda argv: any(
        a.rpartition("/")[2] in ("jupyter", "jupyter-lab") for a in argv[:2]
    ),
}
# The steps that run a lesson's first cell (`lesson = start(N)`) again.
_FIRST_CELL_STEPS = ("open", "run_all", "restart", "first_then_all", "read_through")
FAULTS = (
    "kill the simulation",
    "kill a lesson's node",
    "kill the ros2 daemon",
    "kill a lesson's kernel",
    "kill a busy kernel",
    "kill the Jupyter server",
    "stop the simulation",
    "stop the whole lab",
    "reload the page",
)


def chaos_settings(default_faults: int, default_seed: int | None = None) -> tuple[int, int]:
    """Return (seed, faults) from CHAOS_SEED and CHAOS_FAULTS (see `seed_and_count`)."""
    return seed_and_count("CHAOS_SEED", "CHAOS_FAULTS", default_faults, default_seed)


# the notebooks the page holds unsaved changes of (JupyterLab's own model, exposed to tests)
_UNSAVED = """() => Array.from(window.jupyterapp.shell.widgets('main'))
  .filter((w) => w.context && w.context.model.dirty)
  .map((w) => w.context.path.split('/').pop())"""


@dataclass
class ChaosWalker(Walker):
    """A walk with one fault between steps; the step after a fault may say what happened."""

    faults: int = 0
    _after_fault: bool = False
    _said: bool = False  # the step after a fault said what happened (the learner follows it)
    # open lessons whose kernel a fault killed (a server kill kills them all) and that have not
    # run their first cell since: the first step on each may say so, however much later
    _lost: set[str] = field(default_factory=set)

    def _lab_tree(self, what: str) -> list[psutil.Process]:
        match = _TARGETS[what]
        found = []
        tree = psutil.Process(self.ui.lab.process.pid).children(recursive=True)
        detached = [p for p in psutil.process_iter() if p not in tree and self._owned(p)]
        for process in [*tree, *detached]:
            try:
                if match(process.cmdline()):
                    found.append(process)
            except psutil.Error:
                continue
        return found

    def fault(self, kind: str, rng: random.Random) -> None:
        """Bring fault `kind` on the lab; say what it hit (or that there was nothing to hit)."""
        self.faults += 1
        action, _, what = kind.partition(" ")
        if kind == "reload the page":
            self.log(f"fault {self.faults}: the page is loaded again (its websockets closed)")
            self._reopen_page()
            self._after_fault = True
            return
        if kind == "kill a busy kernel":
            self._kill_busy_kernel(rng)
            return
        if kind == "stop the whole lab":
            self._stop_whole_lab()
            return
        found = self._lab_tree(what)
        if not found:
            self.log(f"fault {self.faults}: {kind}: none runs, nothing done")
            return
        target = rng.choice(found)
        self.log(
            f"fault {self.faults}: {kind} (pid {target.pid}: {' '.join(target.cmdline())[:80]})"
        )
        if action == "kill":
            target.send_signal(signal.SIGKILL)
            if what == "a lesson's kernel":
                self._read_kernel_died()
            if what == "the Jupyter server":
                self._wait_for_server_again(target.pid)
                self._lost |= set(self.opened)  # every kernel died with the server
        else:
            target.send_signal(signal.SIGSTOP)
            time.sleep(STOP_S)
            target.send_signal(signal.SIGCONT)
        self._after_fault = True

    def _has_target(self, kind: str) -> bool:
        """Return whether fault `kind` finds what it acts on (a process, an open lesson)."""
        what = kind.partition(" ")[2]
        return what not in _TARGETS or bool(self._lab_tree(what))

    def _kill_busy_kernel(self, rng: random.Random) -> None:
        """Run All in an open lesson and SIGKILL its kernel while a cell runs."""
        if not self.opened:
            self.log(f"fault {self.faults}: kill a busy kernel: no lesson open, nothing done")
            return
        name = rng.choice(self.opened)
        self.ui.show(name)
        try:
            self.ui.start_run_all()
        except AssertionError as exc:  # it ran to its end before the kill, or never began
            self.log(f"  (the run was not seen busy: {str(exc).splitlines()[0][:120]})")
        kernel_id = self.ui.kernel_id()
        found = [
            p
            for p in self._lab_tree("a lesson's kernel")
            if kernel_id and any(kernel_id in arg for arg in p.cmdline())
        ]
        if not found:
            self.log(f"fault {self.faults}: kill a busy kernel: {name}'s kernel not found")
            return
        time.sleep(rng.uniform(0.0, 3.0))  # somewhere in the run
        self.log(f"fault {self.faults}: kill {name}'s kernel while it runs (pid {found[0].pid})")
        found[0].send_signal(signal.SIGKILL)
        self._read_kernel_died()
        self._after_fault = True

    def _stop_whole_lab(self) -> None:
        """SIGSTOP every process of the lab for STOP_S, then SIGCONT them (a laptop suspended;
        the browser goes on)."""
        root = psutil.Process(self.ui.lab.process.pid)
        tree = [root, *root.children(recursive=True)]
        tree += [p for p in psutil.process_iter() if p not in tree and self._owned(p)]
        self.log(f"fault {self.faults}: stop the whole lab ({len(tree)} processes, {STOP_S:g} s)")
        stopped = []
        for process in tree:
            try:
                process.send_signal(signal.SIGSTOP)
                stopped.append(process)
            except psutil.Error:
                continue
        time.sleep(STOP_S)
        for process in stopped:
            try:
                process.send_signal(signal.SIGCONT)
            except psutil.Error:
                continue
        self._after_fault = True

    def _wait_for_server_again(self, killed: int) -> None:
        """Wait until the lab's launcher has started its server again and it answers; then
        close what JupyterLab said meanwhile, as the learner does."""
        deadline = time.monotonic() + SERVER_BACK_S
        while not (self._server_pid() not in (None, killed) and self.ui.lab.answers()):
            if time.monotonic() > deadline:
                self._record([f"the Jupyter server is not back {SERVER_BACK_S:g} s after a kill"])
                return
            time.sleep(0.2)
        self.log(f"  the server is back ({time.monotonic() - deadline + SERVER_BACK_S:.0f} s)")
        for text in self.ui.dismiss_dialogs():
            self.log(f"  JupyterLab said: {' '.join(text.split())[:160]}")

    def _server_pid(self) -> int | None:
        found = self._lab_tree("the Jupyter server")
        return found[0].pid if found else None

    def _reopen_page(self) -> None:
        """Load the lab's address again, as a learner does after closing the tab or pressing
        F5: JupyterLab restores the open notebooks as last saved; their kernels kept running.

        What was typed since the last save (JupyterLab autosaves every 20 s; the browser asks
        before it leaves unsaved edits) is dropped with the page: a probe cell the walk added
        to a notebook marked unsaved is typed again, as the learner would. A notebook that was
        saved and comes back without its probe is a defect (its next Run All says so)."""
        page, lab = self.ui.page, self.ui.lab
        unsaved = set(page.evaluate(_UNSAVED))
        page.goto(f"{lab.base_url}/lab?token={lab.token}")
        page.locator(".jp-DirListing-item").first.wait_for()
        for name in self.opened:
            label = page.locator(
                ".lm-TabBar-tabLabel", has_text=re.compile(rf"^{re.escape(name)}$")
            )
            label.first.wait_for(state="attached")
        for name in sorted(unsaved & set(self.opened)):
            probe = PROBES.get(lesson_number(name))
            if probe is None:
                continue
            self.ui.show(name)
            if not any(probe[0] in cell.source for cell in self.ui.cells()):
                self.log(f"  {name} was not saved yet: its probe cell is typed again")
                self.ui.add_cell(probe[0])

    def _read_kernel_died(self) -> None:
        """Read JupyterLab's notice of a dead kernel (it starts a new one) and close it, as the
        learner does; say if none came."""
        deadline = time.monotonic() + KERNEL_NOTICE_S
        while time.monotonic() < deadline and "appears to have died" not in self.ui.dialog_text():
            time.sleep(0.2)
        said = self.ui.dismiss_dialogs()
        for text in said:
            self.log(f"  JupyterLab said: {' '.join(text.split())[:160]}")
            if "appears to have died" in text:
                self._lost |= {name for name in self.opened if f"/{name}" in text}
        if not any("appears to have died" in text for text in said):
            self.log("  (no notice of the dead kernel: its notebook may not be in front)")

    def _record(self, problems: list[str]) -> None:
        if self._after_fault:  # a course error right after a fault says what happened: fine
            said = [p for p in problems if " says: " in p]
            for line in said:
                self.log(f"  said after the fault: {line.splitlines()[0][:160]}")
            self._said = self._said or bool(said)
            problems = [p for p in problems if p not in said]
        super()._record(problems)

    def whole_lab_problems(self) -> list[str]:
        """Return what keeps the lab from being whole (checked until WHOLE_WITHIN_S)."""
        deadline = time.monotonic() + WHOLE_WITHIN_S
        while True:
            problems = self._graph_and_strays()
            if not problems or time.monotonic() > deadline:
                return problems
            time.sleep(1.0)

    def _graph_and_strays(self) -> list[str]:
        problems = []
        terminal = Terminal(self.ui.page, self.ui.lab.base_url, self.ui.lab.token)
        try:
            nodes, _ = terminal.run_to_end("ros2 node list")
            names = [n.strip() for n in _plain(nodes).splitlines() if n.strip().startswith("/")]
            twice = sorted(n for n, count in Counter(names).items() if count > 1)
            if twice or names.count("/mujoco") > 1:
                problems.append(f"`ros2 node list` lists a name twice: {names}")
        finally:
            terminal.close()
        lab = psutil.Process(self.ui.lab.process.pid)
        inside = {lab.pid, *(p.pid for p in lab.children(recursive=True))}
        problems += [
            f"a process of the lab's domain outside it: {p}" for p in self._strays(inside)
        ]
        return problems

    def _owned(self, process: psutil.Process) -> bool:
        """Return whether `process` runs detached but is the lab's (its owner tag names it)."""
        try:
            return process.environ().get(OWNER_ENV) == owner_tag(self.ui.lab.process.pid)
        except psutil.Error:
            return False

    def _strays(self, inside: set[int]) -> list[str]:
        """Return the live processes of the lab's ROS domain that are neither in the lab's tree
        nor owned by the lab (a daemon a command started again after the lab's was killed runs
        detached, tagged with its lab, and ends with it). Only this network namespace's: a
        container's lab may lease the same domain number, and no DDS message crosses to it
        (ci, beside the image checks: the container's world was listed as a stray)."""
        strays = []
        network = os.stat("/proc/self/ns/net").st_ino
        for process in psutil.process_iter():
            try:
                if os.stat(f"/proc/{process.pid}/ns/net").st_ino != network:
                    continue
                mine = process.environ().get("ROS_DOMAIN_ID") == str(self.ui.lab.domain_id)
                outside = process.pid not in inside and process.pid != os.getpid()
                outside = outside and not self._owned(process)
                if mine and outside and process.status() != psutil.STATUS_ZOMBIE:
                    strays.append(f"{process.pid} {' '.join(process.cmdline())[:100]}")
            except (psutil.Error, OSError):
                continue
        return strays

    def chaos_walk(self, seed: int, faults: int, *, every_kind: bool = False) -> None:
        """Walk one step, then one fault and one step, `faults` times; check the lab is whole
        after each step that follows a fault. With `every_kind`, the faults are each of FAULTS
        once, in the seed's order (`faults` is then their number)."""
        self.log(f"chaos seed: {seed} (replay: CHAOS_SEED={seed} CHAOS_FAULTS={faults})")
        rng = random.Random(seed)
        self.reading = random.Random(seed + 1)
        kinds = rng.sample(FAULTS, len(FAULTS)) if every_kind else None
        # each kind once: from a lesson whose world runs, so that every fault finds its target
        self.do(Step("open", WORLD_FIRST) if every_kind else self.choose(rng))
        for index in range(len(kinds) if kinds else faults):
            if not self.can_go_on():
                return
            kind = kinds[index] if kinds else rng.choice(FAULTS)
            if kinds and not self._has_target(kind):  # lesson 7 again: its world and node
                self.do(Step("first_then_all", WORLD_FIRST))
            self.fault(kind, rng)
            step = self.choose(rng)
            self._after_fault = self._after_fault or step.lesson in self._lost
            self.do(step)
            self._after_fault = False
            if self._said or step.kind in _FIRST_CELL_STEPS:  # it has run `start(N)` again
                self._lost.discard(step.lesson)
            if self._said:  # as the message says: the lesson's first cell, then the rest
                self._said = False
                self.do(Step("first_then_all", step.lesson))
            self._at = f"after step {self.steps}"
            self._record(self.whole_lab_problems())
        self.do(Step("check_graph", "the lab"))
