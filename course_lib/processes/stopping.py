"""`make stop`: stop the course's processes like Ctrl-C, then harder, and say what stopped.

It stops what the course started and the ROS processes of a stopped lab's domain; a learner's
own programs started from a lab terminal keep running and are listed. Its reach is the clone
it runs from: the course processes another clone started (another lab, a class hub and its
learners' labs, their daemons) keep running and are listed, unless `everything` is asked for.

Which processes count is ownership.py's rule. Each one gets SIGINT (only those whose parent is
not itself being stopped: a lab stops its JupyterLab, a launch its nodes), then whatever still
runs after a grace time gets SIGTERM, then SIGKILL. A process started in a process group of its
own (every `spawn`ed child) is signalled with its group, as `ChildProcess.stop` does. A lab
terminal's shell gets SIGHUP where the others get SIGTERM: what a closing terminal sends, and
what makes the shell hang up its jobs (an interactive shell ignores SIGTERM, and a shell killed
by SIGKILL leaves its jobs running). Last, it removes the shared-memory segments that killed
ROS processes left in /dev/shm (shm_segments.py).
"""

from __future__ import annotations

import contextlib
import signal
from dataclasses import dataclass, field

from ..core.host.signalling import send
from ..core.paths import REPO_ROOT
from ..core.waiting import wait_until
from .ownership import CourseProcess, course_processes, current_lab, own_programs, read_process
from .shm_segments import Swept, sweep_stale_segments

__all__ = ["StopReport", "Stopped", "stop_course", "stop_processes"]

GRACE_S = 10.0  # a lab stops JupyterLab, its kernels and their nodes within this
TERM_S = 3.0
KILL_S = 2.0


@dataclass(frozen=True)
class Stopped:
    """One course process that is gone, and the signal after which it went."""

    name: str
    pid: int
    signal: str


@dataclass
class StopReport:
    """What `make stop` stopped, what it could not stop, and the lab it left running."""

    stopped: list[Stopped] = field(default_factory=list)
    left: list[CourseProcess] = field(default_factory=list)
    kept_lab: int | None = None
    kept_own: list[CourseProcess] = field(default_factory=list)
    kept_other: list[CourseProcess] = field(default_factory=list)  # another clone's
    swept: Swept = field(default_factory=Swept)

    def render(self) -> str:
        """Return the text `make stop` prints: one line per process."""
        lines = []
        if self.stopped:
            lines.append(f"Stopped {len(self.stopped)} course process(es):")
            for s in self.stopped:
                how = "" if s.signal == "SIGINT" else f" after {s.signal}"
                lines.append(f"  {s.name} (pid {s.pid}){how}")
        else:
            lines.append("No course process runs.")
        lines += [f"Could not stop {p.name} (pid {p.pid})." for p in self.left]
        swept = self.swept.sentence()
        lines += [swept] if swept else []
        if self.kept_own:
            lines.append(
                f"Left running {len(self.kept_own)} program(s) of yours, started from a lab "
                "(not by the course, no ROS process):"
            )
            lines += [f"  {' '.join(p.info.argv)[:120]} (pid {p.pid})" for p in self.kept_own]
        if self.kept_other:
            clones = sorted({p.info.clone or "a clone it does not name" for p in self.kept_other})
            lines.append(
                f"Left running {len(self.kept_other)} course process(es) of another clone "
                f"({', '.join(clones)}); `python -m course_lib stop --all` stops them too:"
            )
            lines += [f"  {p.name} (pid {p.pid})" for p in self.kept_other]
        if self.kept_lab is not None:
            lines.append(
                f"This terminal belongs to the lab (pid {self.kept_lab}): its JupyterLab and "
                "terminals keep running. To stop the lab too, press Ctrl-C where `make lab` runs."
            )
        return "\n".join(lines)


def _same(proc: CourseProcess) -> bool:
    info = read_process(proc.pid)
    return info is not None and info.start == proc.info.start


def _signal(proc: CourseProcess, sig: signal.Signals) -> signal.Signals:
    """Send `sig` (SIGHUP for SIGTERM to a terminal's shell); return the signal sent."""
    if sig == signal.SIGTERM and proc.info.terminal_shell:
        sig = signal.SIGHUP  # the terminal hangs up: so does the shell, and its jobs
    if not _same(proc):  # gone, or its pid reused: never signal someone else
        return sig
    reason = f"`make stop`: {proc.name} is a course process ({proc.reason})"
    with contextlib.suppress(ProcessLookupError, PermissionError):
        send(proc.pid, sig, group=proc.info.pgid == proc.pid, reason=reason)
    return sig


def _wait_gone(pending: dict[int, CourseProcess], timeout: float) -> list[int]:
    """Wait until every pending process is gone or `timeout` passes; return those gone."""

    def gone() -> list[int]:
        return [pid for pid, proc in pending.items() if not _same(proc)]

    # polling /proc: a non-child's exit has no event to wait on
    wait_until(lambda: len(gone()) == len(pending), timeout, interval=0.05)
    return gone()


def stop_processes(found: list[CourseProcess], grace_s: float, report: StopReport) -> None:
    """Stop the processes `found` (and only them), adding to `report` how each went."""
    pending = {proc.pid: proc for proc in found}
    roots = [proc for proc in found if proc.info.ppid not in pending]
    stages = ((signal.SIGINT, grace_s), (signal.SIGTERM, TERM_S), (signal.SIGKILL, KILL_S))
    for sig, wait_s in stages:
        sent: dict[int, signal.Signals] = {}
        for proc in roots if sig == signal.SIGINT else list(pending.values()):
            sent[proc.pid] = _signal(proc, sig)
        for pid in _wait_gone(pending, wait_s):
            proc = pending.pop(pid)
            report.stopped.append(Stopped(proc.name, pid, sent.get(pid, sig).name))
        if not pending:
            return
    report.left += pending.values()


def stop_course(
    *, grace_s: float = GRACE_S, rounds: int = 3, everything: bool = False
) -> StopReport:
    """Stop this user's course processes of this clone (of every clone with `everything`),
    never this command, its ancestors or its lab."""
    report = StopReport(kept_lab=current_lab())
    here = str(REPO_ROOT)
    seen: set[int] = set()
    for _ in range(rounds):  # a stopped process may leave children that are leftovers now
        found = [p for p in course_processes() if p.pid not in seen]
        if not found:
            break
        seen |= {p.pid for p in found}
        mine = [p for p in found if everything or p.info.clone == here]
        report.kept_other += [p for p in found if p not in mine]
        stop_processes(mine, grace_s, report)
        grace_s = TERM_S
    report.kept_other = [p for p in report.kept_other if _same(p)]
    report.kept_own = own_programs()
    report.swept = sweep_stale_segments()
    return report
