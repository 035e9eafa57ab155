"""A learner's walk through the lessons in one lab: steps, their checks, and the defects found.

Every step is what a learner does in JupyterLab (open a lesson and Run All, restart a kernel
and Run All, run one cell again, ...), each lesson left running. A step's checks that fail are
recorded as defects and the walk goes on where it can; `Walker.summary()` says what was found.
A random walk prints its seed and every step, so `WALK_SEED=... WALK_STEPS=...` replays it.
"""

from __future__ import annotations

import os
import random
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from lab_graph import graph_problems
from lab_nodes import hosts_of, node_processes
from lab_ui import LabPage
from lesson_checks import (
    LESSONS,
    PROBES,
    WORLD_LESSONS,
    cell_problems,
    lesson_number,
    run_problems,
)
from pace import MACHINE_PACE, MISTAKES, Pace
from terminal import Terminal

__all__ = ["Step", "Walker", "seed_and_count", "walk_settings"]

# Cells a learner may run again at any time, in any state of the lab (never a cell whose
# answer depends on the cell before it, such as lesson 2's `lesson.stop`).
RERUNNABLE = (
    "lesson = start(",
    "environment_report()",
    "%ros2 pkg executables",
    "%ros2 node list",
    "%ros2 topic list",
    "%ros2 param list",
    "compare_topics()",
    "lesson.show_source(",
    "world = lesson.world(",
    "%ros2 run parameter_tests param_vel",
    "%ros2 run parameter_descriptors descriptor_vel",
    "plot = lesson.speed_plot()",
    "events = lesson.events_table()",
    "lesson.self_check()",
)
OPEN_CHANCE = 0.6  # of opening one more lesson, while one is left to open


def seed_and_count(
    seed_env: str, count_env: str, default_count: int, default_seed: int | None = None
) -> tuple[int, int]:
    """Return (seed, count) from the environment's `seed_env` and `count_env`; without a seed
    there, `default_seed`, else a random seed (printed by the walk, so it replays)."""
    seed = os.environ.get(seed_env)
    count = os.environ.get(count_env)
    if seed:
        chosen = int(seed)
    elif default_seed is not None:
        chosen = default_seed
    else:
        chosen = random.SystemRandom().randrange(1_000_000)
    return chosen, int(count) if count else default_count


def walk_settings(default_steps: int, default_seed: int | None = None) -> tuple[int, int]:
    """Return (seed, steps) from WALK_SEED and WALK_STEPS (see `seed_and_count`)."""
    return seed_and_count("WALK_SEED", "WALK_STEPS", default_steps, default_seed)


def _say(line: str) -> None:
    print(line, flush=True)


@dataclass
class Step:
    """One step of a walk: what the learner does, to which lesson."""

    kind: str
    lesson: str
    detail: str = ""

    def __str__(self) -> str:
        return f"{self.kind} {self.lesson}{f' ({self.detail})' if self.detail else ''}"


@dataclass
class Walker:
    """Walks one lab's lessons in one browser tab and records what goes wrong."""

    ui: LabPage
    artifacts: Path
    say: Callable[[str], None] = _say
    opened: list[str] = field(default_factory=list)
    defects: list[str] = field(default_factory=list)
    steps: int = 0
    pace: Pace = MACHINE_PACE  # how long the learner reads between cells and steps
    reading: random.Random = field(default_factory=lambda: random.Random(0))  # reading times
    _at: str = "start"  # the step running, to name where a defect was found
    _nodes: list[str] = field(default_factory=list)  # the lab's node processes, last seen

    # --- the steps ------------------------------------------------------------------------------
    def open(self, name: str) -> None:
        """Open lesson `name` from the file browser, Run All, check the whole run."""
        self.ui.open(name)
        self.opened.append(name)
        self.ui.run_all()
        number = lesson_number(name)
        if number in PROBES:  # added once, then part of every later Run All
            self.ui.add_cell(PROBES[number][0])
        self._check_run(name)

    def run_all(self, name: str) -> None:
        """Bring an open lesson to the front and Run All again."""
        self.ui.show(name)
        self.ui.run_all()
        self._check_run(name)

    def restart(self, name: str) -> None:
        """Kernel > Restart Kernel and Run All Cells… in an open lesson."""
        self.ui.show(name)
        self.ui.restart_and_run_all()
        self._check_run(name)

    def first_then_all(self, name: str) -> None:
        """Run an open lesson's first cell again (`lesson = start(N)`), then Run All."""
        self.ui.show(name)
        first = self.ui.run_cell(self.ui.cell_with("lesson = start("))
        self._record(cell_problems(name, first))
        self.ui.run_all()
        self._check_run(name)

    def rerun_cell(self, name: str, source: str) -> None:
        """Run one cell of an open lesson again; it must show no error."""
        self.ui.show(name)
        cell = self.ui.run_cell(self.ui.cell_with(source))
        self._record(cell_problems(name, cell))

    def read_through(self, name: str) -> None:
        """Run a lesson cell by cell from the top, reading after each (opened first if need be)."""
        first = name not in self.opened
        if first:
            self.ui.open(name)
            self.opened.append(name)
        else:
            self.ui.show(name)
        for index in range(len(self.ui.cells())):
            if not self.ui.cells()[index].source.strip():  # Shift+Enter on the last cell adds one
                continue
            cell = self.ui.run_cell(self.ui.cells()[index])
            self._record(cell_problems(name, cell))
            self.read(cell.source)
        if first and lesson_number(name) in PROBES:  # as `open` adds it
            self.ui.add_cell(PROBES[lesson_number(name)][0])
        self._check_run(name)

    def mistake(self, name: str, code: str) -> None:
        """Add a mistaken cell to an open lesson and run it: a hint, never an error."""
        self.ui.show(name)
        cell = self.ui.add_cell(code)
        self._record(cell_problems(name, cell))
        expected = next(m.expected() for m in MISTAKES if m.code == code)
        if "Hint: " not in cell.text or not any(text in cell.text for text in expected):
            self._record([f"{name}: `{code}` should show a hint with {expected}: {cell.text}"])
        self.read(code)

    def read(self, source: str = "") -> None:
        """Read for as long as the pace draws after the cell `source` (a person between cells)."""
        pause = self.pace.pause_s(self.reading, source)
        if pause >= 5.0:
            self.log(f"  (reads {pause:.0f} s)")
        time.sleep(pause)

    def check_graph(self) -> None:
        """Check the lab's graph from a lab terminal: one /mujoco and one /clock publisher once
        a lesson started the world, none before."""
        world = any(lesson_number(name) in WORLD_LESSONS for name in self.opened)
        terminal = Terminal(self.ui.page, self.ui.lab.base_url, self.ui.lab.token)
        try:
            self._record(graph_problems(terminal, worlds=int(world)))
        finally:
            terminal.close()

    # --- running steps and recording defects -----------------------------------------------------
    def do(self, step: Step) -> None:
        """Do one step and record, instead of raising, whatever failed in it."""
        if step.kind == "check_graph":  # the end of a walk, not one of its steps
            self._at = "end of the walk"
        else:
            self.steps += 1
            self._at = f"step {self.steps}"
        self.log(f"walk {self._at}: {step}")
        started = time.monotonic()
        defects_before = len(self.defects)
        try:
            left = self.ui.dismiss_dialogs()  # what an earlier step left open
            self._record([f"a dialog was left open: {text}" for text in left])
            if step.kind in ("rerun_cell", "mistake"):
                getattr(self, step.kind)(step.lesson, step.detail)
            elif step.kind == "check_graph":
                self.check_graph()
            else:
                getattr(self, step.kind)(step.lesson)
        except AssertionError as exc:
            self._record([f"{exc}"])
        except Exception as exc:  # a Playwright timeout or a closed page: a defect too
            self._record([f"{type(exc).__name__}: {exc}"])
        self.log(f"  ({time.monotonic() - started:.0f} s)")
        self._log_nodes()
        if any("param_vel_node" in defect for defect in self.defects[defects_before:]):
            self._log_hosts("/param_vel_node")

    def _log_hosts(self, node: str) -> None:
        """Log which processes hold `node`'s /parameter_events publishers (a name listed more
        often than its processes: which process is the extra one?)."""
        terminal = Terminal(self.ui.page, self.ui.lab.base_url, self.ui.lab.token)
        try:
            info, _ = terminal.run_to_end("ros2 topic info /parameter_events --verbose")
            for line in hosts_of(info.replace("\r\n", "\n"), node) or [f"no {node} found"]:
                self.log(f"  host: {line}")
        except Exception as exc:  # a diagnosis only: never a defect of its own
            self.log(f"  host: could not list {node}'s processes: {exc}")
        finally:
            terminal.close()

    def _log_nodes(self) -> None:
        """Log the lab's node processes when a step changed them (who started which)."""
        nodes = node_processes(self.ui.lab)
        if nodes != self._nodes:
            self._nodes = nodes
            self.log(f"  nodes: {'; '.join(nodes) or 'none'}")

    def _check_run(self, name: str) -> None:
        self._record(run_problems(name, self.ui.cells()))

    def _record(self, problems: list[str]) -> None:
        for problem in problems:
            self.defects.append(f"{self._at}: {problem}")
            self.log(f"  DEFECT {len(self.defects)}: {problem}")
        shot = self.artifacts / f"{self._at.replace(' ', '_')}_defect.png"
        if problems and not shot.exists():
            self.ui.screenshot(shot)

    def log(self, line: str) -> None:
        """Say `line` and keep it in the test's walk.log (a soak's record)."""
        self.say(line)
        with open(self.artifacts / "walk.log", "a", encoding="utf-8") as file:
            file.write(line + "\n")

    def summary(self, seed: int | None = None) -> list[str]:
        """Return the walk's summary, one line each: steps, defects, seed."""
        lines = [f"steps walked: {self.steps}", f"defects found: {len(self.defects)}"]
        return [*lines, f"seed: {seed}"] if seed is not None else lines

    def report(self, seed: int | None = None) -> str:
        """Return the summary and every defect, for a failure message."""
        return "\n".join([*self.summary(seed), *self.defects])

    # --- a random walk --------------------------------------------------------------------------
    def choose(self, rng: random.Random) -> Step:
        """Choose the next step: open a lesson not open yet (some chance while one is left), or
        do something to an open one."""
        closed = [name for name in LESSONS if name not in self.opened]
        if not self.opened or (closed and rng.random() < OPEN_CHANCE):
            return Step("open", rng.choice(closed))
        name = rng.choice(self.opened)
        kinds = ["run_all", "restart", "first_then_all", "rerun_cell", "rerun_cell"]
        mistakes = [m.code for m in MISTAKES if m.lesson == lesson_number(name)]
        if self.pace is not MACHINE_PACE:  # a person reads through lessons and makes mistakes
            kinds += ["read_through", *(["mistake"] if mistakes else [])]
        kind = rng.choice(kinds)
        if kind == "mistake":
            return Step(kind, name, rng.choice(mistakes))
        if kind != "rerun_cell":
            return Step(kind, name)
        sources = [source for source in RERUNNABLE if source in _sources(name)]
        return Step(kind, name, rng.choice(sources))

    def can_go_on(self) -> bool:
        """Return False, recording why, once the lab or the browser tab is gone."""
        if self.ui.lab.process.alive and not self.ui.page.is_closed():
            return True
        self._record([f"the lab or its browser tab stopped: the walk ends\n{self.ui.lab.text()}"])
        return False

    def random_walk(self, seed: int, steps: int) -> None:
        """Walk `steps` random steps from `seed`, then check the graph from a terminal."""
        pace = "" if self.pace is MACHINE_PACE else f" WALK_PACE={self.pace.name}"
        self.log(f"walk seed: {seed} (replay: WALK_SEED={seed} WALK_STEPS={steps}{pace})")
        rng = random.Random(seed)
        self.reading = random.Random(seed + 1)
        for _ in range(steps):
            if not self.can_go_on():
                return
            self.do(self.choose(rng))
            self.read()
        self.do(Step("check_graph", "the lab"))


def _sources(name: str) -> str:
    """Return the code of lesson `name` as stored in notebooks/ (to know what cells it has)."""
    import nbformat

    from course_lib.core.paths import NOTEBOOKS_DIR

    notebook = nbformat.read(NOTEBOOKS_DIR / name, as_version=4)
    return "\n".join(cell.source for cell in notebook.cells if cell.cell_type == "code")
