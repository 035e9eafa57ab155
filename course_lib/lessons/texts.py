"""The lesson cells that state a configured value, rendered from config/course.yaml (pure).

A learner reads and types literal numbers, as in the ROS 2 tutorial and as a terminal needs
them (`velocity 0.2`, not an expression); an instructor changes course.yaml and runs
`make notebooks`, which renders these cells (found by their cell id) before executing the
lesson, so prose, commands and stored outputs all show the configured values. Each rendered
notebook records the settings it was made with (`metadata.course_settings`), so
`make check-config` can say which lessons still show other values. Edit a templated cell in
its lesson's module (lessons/catalogue/), not in the notebook: `make notebooks` would put that
module's text back.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..config.course import CourseSettings
from .catalogue import LESSONS
from .catalogue.spec import Template

__all__ = ["METADATA_KEY", "TEMPLATES", "render_cells", "settings_used", "stale_notebooks"]

METADATA_KEY = "course_settings"

# notebook file name -> cell id -> template (each lesson's module in lessons/catalogue/)
TEMPLATES: dict[str, dict[str, Template]] = {
    spec.notebook: dict(spec.templates) for spec in LESSONS if spec.templates
}
# notebook file name -> the settings its cells and outputs depend on
_USED: dict[str, tuple[str, ...]] = {
    spec.notebook: spec.settings for spec in LESSONS if spec.settings
}


def settings_used(name: str, settings: CourseSettings) -> dict[str, Any]:
    """Return the settings notebook `name` depends on, by dotted key ({} for none)."""
    found: dict[str, Any] = {}
    for key in _USED.get(name, ()):
        value: Any = settings
        for part in key.split("."):
            value = getattr(value, part)
        found[key] = value
    return found


def render_cells(name: str, nb: Any, settings: CourseSettings) -> list[str]:
    """Render notebook `name`'s templated cells into `nb` (nbformat); return the changed ids."""
    templates = TEMPLATES.get(name, {})
    changed = []
    for cell in nb.cells:
        template = templates.get(cell.get("id"))
        if template is not None and cell.source != template(settings):
            cell.source = template(settings)
            changed.append(cell.id)
    missing = set(templates) - {c.get("id") for c in nb.cells}
    if missing:
        raise ValueError(
            f"{name} has no cell {sorted(missing)[0]}: update its module in lessons/catalogue/"
        )
    used = settings_used(name, settings)
    if used:
        nb.metadata[METADATA_KEY] = used
    return changed


def stale_notebooks(folder: Path, settings: CourseSettings) -> list[str]:
    """Return a line for each notebook in `folder` made with other settings than `settings`."""
    import json

    lines = []
    for name in sorted(_USED):
        path = folder / name
        if not path.exists():
            continue
        nb = json.loads(path.read_text(encoding="utf-8"))
        made = nb.get("metadata", {}).get(METADATA_KEY, {})
        now = settings_used(name, settings)
        differ = [f"{k} {made.get(k)!r} (now {v!r})" for k, v in now.items() if made.get(k) != v]
        if differ:
            lines.append(
                f"notebooks/{name} shows the values of other settings: {', '.join(differ)}; "
                f"run `make notebooks ARGS={name}` to render and re-execute it."
            )
    return lines
