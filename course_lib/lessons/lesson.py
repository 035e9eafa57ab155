"""The lesson object every notebook makes in its first cell: `lesson = start(7)`.

It holds the session, the instructor's settings and the helpers the lessons call: start the
world, run and stop nodes, show their log lines, show and edit files, and the self-check.
"""

from __future__ import annotations

import os
import re
import threading
import time
from pathlib import Path
from typing import Any

from ..core.errors import CourseError
from ..core.paths import REPO_ROOT
from ..processes.children import ChildProcess
from . import files
from .catalogue import lesson_spec, run_checks
from .report import SelfCheck
from .running import RUN_PREFIX, LogLines
from .settings import CourseSettings

__all__ = ["Lesson", "LogLines"]

_RCLPY_OWN = re.compile(r"'(use_sim_time|start_type_description_service)' .* is not declared")
_FAILED_LINES = 8  # what `stop` shows of a node that failed on Ctrl-C: its traceback's end


class Lesson:
    """One lesson's state: session, settings, the world and the nodes it started."""

    def __init__(self, number: int, session: Any, settings: CourseSettings) -> None:
        self.number = number
        self.title = lesson_spec(number).title
        self.session = session
        self.settings = settings
        self.started: dict[str, ChildProcess] = {}
        self.state: dict[str, Any] = {}
        self.started_at = time.time()  # files older than this come from an earlier run
        self.learner_dir = files.LEARNER_DIR  # notebooks/my_files/: the learner's, not git's
        self._world: Any = None
        self.replay: Any = None  # a driving lesson's recording of its run (lessons/replay)
        self._lock = threading.Lock()

    def __repr__(self) -> str:
        return f"Lesson {self.number} · {self.title}"

    @property
    def attached_world(self) -> Any:
        """Return the world this lesson started or attached to (None before), alive or not."""
        return self._world

    @property
    def velocity(self) -> float:
        """Return the instructor's default velocity in m/s (config/course.yaml)."""
        return self.settings.default_velocity_mps

    # --- the world -------------------------------------------------------------------------
    def world(self, *, show: bool = True, config: str | None = None) -> Any:
        """Start the simulated world (or reuse it), put the robot at its start pose, show it."""
        from ..notebook import start_world

        path = str(REPO_ROOT / "config" / config) if config else None
        world = start_world(self.session, show=show, config=path)  # shows the 3D view
        world.reset()  # at rest too: the reset zeroes the wheels' command
        self._world = world
        if self.replay is not None:
            self.replay.restart()  # the replay shows the run from the start pose on
        whose = "Your lab's robot, the one every notebook shows," if world.shared else "The robot"
        print(f"{whose} is back at its start pose, standing still.")
        return world

    def _running_lab_world(self) -> Any:
        """Return the lab's world if it runs (attached as it is, robot left where it is)."""
        from ..lab import machine_client
        from ..notebook import start_world

        client = machine_client()
        if client is None:
            return None
        status = client.request("world.status", timeout=5.0)
        if not status.get("running"):
            return None
        return start_world(self.session, show=False, config=status.get("config"))

    @property
    def current_world(self) -> Any:
        """Return the running world; raise a CourseError that says how to start it.

        In a lab whose world runs, a kernel that has not asked for it yet (its first cell was
        run again, or the kernel restarted) gets the lab's world: every number comes from it.
        """
        if self._world is None or not self._world.alive:
            self._world = self._running_lab_world()
        if self._world is None or not self._world.alive:
            raise CourseError(
                "The simulation is not running in this lesson.",
                hint="run the cell with `lesson.world()` first.",
            )
        return self._world

    # --- nodes -------------------------------------------------------------------------------
    def node(self, name: str) -> ChildProcess:
        """Return the latest process of executable `name` started in this session."""
        found = [c for c in self.session.children if c.name == name]
        if found:
            self.started[name] = found[-1]
        if name not in self.started:
            raise CourseError(
                f"No process '{name}' was started in this lesson.",
                hint=f"run its `%ros2 run ... {name}` cell first.",
            )
        return self.started[name]

    def stop_nodes(self) -> None:
        """Stop every node this session started; the simulation and its 3D view keep running."""
        keep: set[int] = set()
        if self._world is not None:
            keep.add(self._world.process.pid)
            if self._world.viewer is not None:
                keep.add(self._world.viewer.process.pid)
        for child in self.session.children:
            if child.pid not in keep:
                child.stop()

    def run(self, package: str, executable: str, *args: str, timeout: float = 10.0) -> LogLines:
        """Start a node like `ros2 run`; show its first log line, or how it failed."""
        from .running import run_node

        return run_node(self, package, executable, *args, timeout=timeout)

    def log_lines(self, name: str, count: int = 3, timeout: float = 10.0) -> LogLines:
        """Wait for the next `count` log lines of node process `name` and return them."""
        child = self.node(name)
        start = len(child.lines)
        deadline = time.monotonic() + timeout
        while len(child.lines) < start + count and time.monotonic() < deadline:
            if child.wait_for_line(lambda _line: True, 0.5) is None and not child.alive:
                break
        return LogLines([ln.text for ln in child.lines[start : start + count]])

    def stop(self, name: str) -> files.Text:
        """Stop node process `name` as Ctrl-C in its terminal does; say how it ended, and
        what it printed last if it failed (its traceback, as its terminal would show it)."""
        child = self.node(name)
        code = child.stop()
        said = f"{name} stopped (Ctrl-C), exit code {code}."
        if code == 0:
            return files.Text(said)
        last = [ln.text for ln in child.lines if ln.text.strip()][-_FAILED_LINES:]
        return files.Text("\n".join([said, "Its last lines:", *(f"  {text}" for text in last)]))

    def exit_report(self, name: str, timeout: float = 10.0) -> LogLines:
        """Wait for node process `name` to end; return its last line and exit code."""
        child = self.node(name)
        code = child.wait(timeout)
        if code is None:
            return LogLines([f"{name} is still running."])
        last = [ln.text for ln in child.lines if ln.text.strip()][-1:]
        return LogLines([*last, f"{RUN_PREFIX} Process exited with failure {code}"])

    # --- files -------------------------------------------------------------------------------
    def show_file(self, path: str | os.PathLike[str], marks: tuple[int, ...] = ()) -> Any:
        """Show a file with line numbers (`marks`: lines to point at)."""
        text = Path(path).read_text(encoding="utf-8")
        body = files.numbered(text, marks=set(marks)) if marks else text
        return files.FileView(files.display_path(path), body)

    def package_file(self, package: str, relpath: str) -> Path:
        """Return the source path of a file of a package in rosject/ (not the installed copy)."""
        from ..core.paths import ROSJECT_DIR

        path = ROSJECT_DIR / package / relpath
        if not path.exists():
            raise CourseError(f"{package} has no file {relpath}", hint="check the name.")
        return path

    def show_source(self, package: str, relpath: str, *, find: tuple[str, ...] = ()) -> Any:
        """Show a package file from rosject/, marking the lines that contain any of `find`."""
        path = self.package_file(package, relpath)
        lines = path.read_text(encoding="utf-8").splitlines()
        marks = tuple(n for n, line in enumerate(lines, 1) if any(f in line for f in find))
        return self.show_file(path, marks)

    def learner_file(self, name: str) -> Path:
        """Return the path of a file the learner owns (in notebooks/my_files/, not in git)."""
        return self.learner_dir / name

    def ros2_to_file(self, command: str, path: str | os.PathLike[str]) -> files.Text:
        """Run `ros2 <command> > path` (stdout into the file, atomically); show the line."""
        from ..ros2.api.nodes_and_params import ros2

        result = ros2(command)
        if not result.ok:
            raise CourseError(result.text.strip(), hint="is the node running? `%ros2 node list`")
        files.atomic_write(path, result.stdout)
        return files.Text(f"$ ros2 {command} > {files.display_path(path)}")

    def copy_file(self, source: str | os.PathLike[str], name: str) -> Path:
        """Copy a file into the learner's folder as `name`; return the new path."""
        text = Path(source).read_text(encoding="utf-8")
        return files.atomic_write(self.learner_file(name), text)

    def edit_file(self, path: str | os.PathLike[str], old: str, new: str) -> files.Text:
        """Replace `old` by `new` in a file (as an editor would) and return the diff."""
        before = Path(path).read_text(encoding="utf-8")
        if old not in before:
            raise CourseError(
                f"{files.display_path(path)} has no text {old!r}",
                hint="show the file and copy the exact line to change.",
            )
        files.atomic_write(path, before.replace(old, new, 1))
        return files.Text(
            files.diff_text(before, before.replace(old, new, 1), files.display_path(path))
        )

    # --- self-check ----------------------------------------------------------------------------
    def self_check(self) -> SelfCheck:
        """Run this lesson's self-check: what passed, and what to try for what did not."""
        from .progress.client import report_progress

        print(f"Checking lesson {self.number}'s nodes, files and robot ...", flush=True)
        result = SelfCheck.of(self.number, run_checks(self))
        report_progress(result)  # on a hub only; never raises, never waits
        if self.replay is not None:
            from .replay import show_replay

            show_replay(self)  # a driving lesson's run, saved when its self-check ends
        return result

    def save_replay(self) -> Any:
        """Save this run's replay (3D motion, speed plot; plays offline) and return its link."""
        from .replay import save_replay

        link = save_replay(self)
        if link is None:
            return files.Text("No motion of the robot was recorded in this lesson yet.")
        return link

    # --- lesson-specific tools (thin doors onto their modules) --------------------------------
    def where(self) -> files.Text:
        """Say where the robot is and how fast it goes (from /odom)."""
        import math

        reading = self.current_world.odom()
        p = reading.pose
        return files.Text(
            f"Robot at x {p.x:.2f} m, y {p.y:.2f} m, heading {math.degrees(p.yaw):.0f}°, "
            f"speed {abs(reading.linear_mps):.2f} m/s."
        )

    def drive_for(self, sim_seconds: float) -> files.Text:
        """Let `sim_seconds` of simulated time pass, then report speed and distance."""
        from .motion import drive_report

        return drive_report(self, sim_seconds)

    def wait_until_stopped(self) -> files.Text:
        """Wait until the robot stands still (from /odom)."""
        from .motion import stop_report

        return stop_report(self)

    def speed_plot(self) -> Any:
        """Show a live plot of /odom speed with every velocity change marked; return it."""
        from ..notebook.widgets import SpeedPlot

        plot = SpeedPlot(self.session)
        plot.show()
        self.state["speed_plot"] = plot  # the replay draws the same samples and marks
        return plot

    def dry_run(self, package: str, file: str, *args: str) -> files.Text:
        """Show what `ros2 launch ... ` would start, with each parameter's origin and traps."""
        from ..launch.command.dry_run import dry_run

        report = dry_run(package, file, *args)
        # rclpy declares these two on every node; the dry run does not know it yet (reported).
        report.warnings = [w for w in report.warnings if not _RCLPY_OWN.search(w)]
        return files.Text(report.render())

    def launch(self, package: str, file: str | None = None, *args: str) -> Any:
        """Start `ros2 launch package file` (or `ros2 launch path`); show its first lines.

        Stop it with `.stop()`.
        """
        from .launching import start_launch

        return start_launch(self, package, file, *args)

    def events_table(self) -> Any:
        """Show /parameter_events as a live table; return it."""
        from ..notebook.widgets import EventsTable

        table = EventsTable(self.session)
        from IPython.display import display

        display(table)
        return table

    def parameter_panel(self, node: str, save_as: str = "panel_params.yaml") -> Any:
        """Show a panel of `node`'s parameters built from its descriptors; return it."""
        from ..notebook.widgets import ParameterPanel

        panel = ParameterPanel(node, save_path=self.learner_file(save_as), session=self.session)
        from IPython.display import display

        display(panel)
        return panel

    def save_panel(self, panel: Any) -> Any:
        """Save the panel's node's parameters to its params file and show the file."""
        path = panel.save()
        self.state["saved_params"] = path
        return self.show_file(path)

    def history(self, node: str = "/param_vel_node") -> Any:
        """Show each change of `node`'s parameters since it started, and where it came from."""
        from ..notebook.history import node_history

        return node_history(node, self.session.domain_id)

    def reset(self, node: str = "/param_vel_node") -> Any:
        """Set every parameter of `node` back to its start-up value; say what changed."""
        from ..notebook.undo import reset_parameters

        return reset_parameters(node, self.session.domain_id)

    def diff(
        self, node: str = "/param_vel_node", path: str | os.PathLike[str] | None = None
    ) -> Any:
        """Compare `node`'s running values with a params file (or its start-up values)."""
        from ..notebook.undo import diff_parameters

        return diff_parameters(node, self.session.domain_id, path)

    def travel_exercise(self) -> Any:
        """Arm lesson 11's travel exercise (robot to its start pose) and return its checker."""
        from .exercise import TravelExercise

        exercise = TravelExercise(self)
        print(exercise.arm(), end="")
        return exercise

    def _skill(self, kind: str) -> Any:
        from .skills import exercises

        exercise = getattr(exercises, kind)(self)
        print(exercise.arm(), end="")
        return exercise

    def drive_exercise(self) -> Any:
        """Arm lesson 7's exercise (drive a distance in a time) and return its checker."""
        return self._skill("DriveExercise")

    def params_file_exercise(self) -> Any:
        """Arm lesson 9's exercise (start at a speed from an edited dump) and return it."""
        return self._skill("ParamsFileExercise")

    def launch_exercise(self) -> Any:
        """Arm lesson 10's exercise (a launch file that sets the speed) and return it."""
        return self._skill("LaunchExercise")

    def saved_panel_exercise(self) -> Any:
        """Arm lesson 11's exercise (a saved panel value survives a restart) and return it."""
        return self._skill("SavedPanelExercise")
