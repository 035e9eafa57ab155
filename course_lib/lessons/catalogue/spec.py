"""What one lesson is to the course, and the item its self-check returns (pure).

A lesson's module in this folder holds its `SPEC`; the table in `__init__.py` lists them.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

if TYPE_CHECKING:
    from ...config.course import CourseSettings
    from ...processes.children import ChildProcess

__all__ = ["Check", "LessonSpec", "LessonView", "Template", "check"]


@dataclass(frozen=True)
class Check:
    """One self-check item: what was checked, whether it passed, and what to try if not."""

    what: str
    passed: bool
    hint: str = ""


def check(what: str, passed: bool, hint: str = "") -> Check:
    """Return a Check (`passed` coerced to bool)."""
    return Check(what, bool(passed), hint)


# A templated cell's text from the instructor's settings.
Template = Callable[["CourseSettings"], str]


class LessonView(Protocol):
    """What a self-check reads of the lesson object (`lessons/lesson.py` `Lesson`)."""

    number: int
    session: Any  # the kernel's session (session/session.py), or the lab's
    state: dict[str, Any]  # what the lesson's cells left for its check
    started: dict[str, ChildProcess]
    started_at: float

    @property
    def attached_world(self) -> Any: ...

    @property
    def velocity(self) -> float: ...

    def learner_file(self, name: str) -> Path: ...


@dataclass(frozen=True, eq=False)
class LessonSpec:
    """One lesson: its notebook, title, self-check and what it needs of the course.

    Attributes:
        number: the N of `start(N)` and of the notebook's `NN_` prefix.
        notebook: the notebook's file name in notebooks/ (`07_move_the_robot.ipynb`).
        title: the lesson's title (its first cell prints it; the progress page shows it).
        check: its self-check: the lesson object in, the checks run now out.
        driven_node: the node that drives the robot, whose run is recorded for a replay
            (lessons/replay), or "" when the robot does not drive.
        exercises: the names its exercises' attempts are counted under ("07 drive").
        templates: cell id -> template, for the cells rendered from config/course.yaml.
        settings: the dotted settings its cells and outputs depend on (`make check-config`).
        world: whether its cells start (or attach to) the simulated world.
    """

    number: int
    notebook: str
    title: str
    check: Callable[[LessonView], list[Check]]
    driven_node: str = ""
    exercises: tuple[str, ...] = ()
    templates: Mapping[str, Template] = field(default_factory=dict)
    settings: tuple[str, ...] = ()
    world: bool = False
