"""`make check-config`: every instructor file in config/, alone and together, in under a second.

Run before `make lab`, `make notebooks` and `make doctor` too: a broken file stops them before
anything starts, with every problem listed (file, line, key, the allowed range, what to do).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..config.commented import commented_yaml, settings_rows
from ..config.course import CourseSettings
from ..config.loader import check_file, display_path
from ..config.simulation import SimulationSettings
from ..config.together import check_files_together
from ..core.errors import ConfigError, CourseError
from ..core.paths import config_dir, learner_notebooks_dir
from ..hub.provision.settings import HubSettings
from ..lessons.texts import stale_notebooks

__all__ = [
    "HEADERS",
    "SCHEMAS",
    "ConfigReport",
    "check_config",
    "require_valid_config",
    "settings_table_rows",
    "write_comments",
]

SCHEMAS: dict[str, type] = {
    "course.yaml": CourseSettings,
    "simulation.yaml": SimulationSettings,
    "hub.yaml": HubSettings,
}
# Only the class hub reads hub.yaml (`sudo make hub`, as root): the learners' copy of a class
# never carries it (it may hold the demo's password), and their labs check config/ without it.
_HUB_ONLY = "hub.yaml"


# The files whose comments are written from their schema (config/hub.yaml keeps its own).
HEADERS = {
    "course.yaml": """
Instructor settings for the lessons (course_lib.config.course). `make check-config` checks
this file; the first cell of every lesson too, naming the line of any mistake. After a change,
`make notebooks` renders the lessons' texts, commands and stored outputs from it.
Delete a key to get its default. The comments below are written from the schema:
`make check-config ARGS=--write-comments` rewrites them and keeps your values.
""",
    "simulation.yaml": """
The simulated TurtleBot3 world (course_lib.config.simulation). `make check-config` checks it,
alone and with course.yaml (the start pose clear of the obstacles, room for the lessons'
drives); the world checks it when it starts. Restart the world (World.stop(), then
lesson.world()) to apply a change. Delete a key to get its default. The comments below are
written from the schema: `make check-config ARGS=--write-comments` rewrites them.
""",
}


def write_comments(folder: Path | None = None) -> list[Path]:
    """Rewrite the comments of the files in HEADERS from their schema; return those changed."""
    folder = folder or config_dir()
    report = check_config(folder)
    if not report.ok:
        raise CourseError(report.render(), hint="fix those lines first: values are kept.")
    changed = []
    for name, header in HEADERS.items():
        path = folder / name
        text = commented_yaml(report.settings[name], header)
        if path.read_text(encoding="utf-8") != text:
            path.write_text(text, encoding="utf-8")
            changed.append(path)
    return changed


def settings_table_rows() -> list[str]:
    """Return the table of settings in book/guides/instructor-settings.md: one row per key of
    every file in SCHEMAS."""
    head = ["| File | Key | Meaning | Allowed | Default |", "| --- | --- | --- | --- | --- |"]
    return head + [row for name, schema in SCHEMAS.items() for row in settings_rows(name, schema)]


@dataclass
class ConfigReport:
    """What checking the config folder found."""

    folder: Path
    problems: list[ConfigError] = field(default_factory=list)
    settings: dict[str, Any] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        """Return True when every file is valid, alone and together."""
        return not self.problems

    def render(self) -> str:
        """Return the report as the instructor reads it."""
        where = display_path(self.folder)
        if self.ok:
            lines = [f"{where}/: {', '.join(self.settings)} are valid, alone and together."]
            return "\n".join(lines + [f"Note: {note}" for note in self.notes])
        lines = [f"{where}/: {len(self.problems)} problem(s); nothing was started."]
        for problem in self.problems:
            lines += [f"  {problem.message}", f"    Try: {problem.hint}"]
        return "\n".join(lines)


def check_config(folder: Path | None = None) -> ConfigReport:
    """Check every instructor file in `folder` (default: the config folder) alone and together."""
    folder = folder or config_dir()
    report = ConfigReport(folder)
    for name, schema in SCHEMAS.items():
        if name == _HUB_ONLY and not os.access(folder / name, os.R_OK):
            # a learners' copy of a class, or an instructor's file closed to this account
            if (folder / name).exists():
                report.notes.append(f"{name} is closed to this account: only the hub reads it.")
            continue
        value, problems = check_file(folder / name, schema)
        report.problems += problems
        if value is not None:
            report.settings[name] = value
    course, sim = report.settings.get("course.yaml"), report.settings.get("simulation.yaml")
    if course is not None and sim is not None:
        paths = {name: folder / name for name in SCHEMAS}
        report.problems += check_files_together(course, sim, paths)
    if course is not None and report.ok:
        report.notes += stale_notebooks(learner_notebooks_dir(), course)
    return report


def require_valid_config(*, show_notes: bool = True) -> dict[str, Any]:
    """Check the config folder; raise a CourseError listing every problem when it is broken."""
    report = check_config()
    if not report.ok:
        raise CourseError(report.render(), hint="fix those lines, then `make check-config`.")
    for note in report.notes if show_notes else []:
        print(f"Note: {note}")
    return report.settings
