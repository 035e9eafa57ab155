"""`make check-config`: every instructor file in config/, alone and together, in under a second.

Run before `make lab`, `make notebooks` and `make doctor` too: a broken file stops them before
anything starts, with every problem listed (file, line, key, the allowed range, what to do).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .config.course import CourseSettings
from .config.loader import check_file, display_path
from .config.simulation import SimulationSettings
from .config.together import check_files_together
from .errors import ConfigError, CourseError
from .hub.settings import HubSettings
from .lessons.texts import stale_notebooks
from .paths import config_dir, learner_notebooks_dir

__all__ = ["SCHEMAS", "ConfigReport", "check_config", "require_valid_config"]

SCHEMAS: dict[str, type] = {
    "course.yaml": CourseSettings,
    "simulation.yaml": SimulationSettings,
    "hub.yaml": HubSettings,
}


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
            lines = [f"{where}/: {', '.join(SCHEMAS)} are valid, alone and together."]
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
        value, problems = check_file(folder / name, schema)
        report.problems += problems
        if value is not None:
            report.settings[name] = value
    course, sim = report.settings.get("course.yaml"), report.settings.get("simulation.yaml")
    if course is not None and sim is not None:
        paths = {name: folder / name for name in SCHEMAS}
        report.problems += check_files_together(course, sim, paths)
    if course is not None and report.ok:
        report.notes = stale_notebooks(learner_notebooks_dir(), course)
    return report


def require_valid_config(*, show_notes: bool = True) -> dict[str, Any]:
    """Check the config folder; raise a CourseError listing every problem when it is broken."""
    report = check_config()
    if not report.ok:
        raise CourseError(report.render(), hint="fix those lines, then `make check-config`.")
    for note in report.notes if show_notes else []:
        print(f"Note: {note}")
    return report.settings
