"""The lesson catalogue: one module per lesson, one line per lesson in `LESSONS` (pure).

A lesson is its notebook `notebooks/NN_name.ipynb`, its module here (`lNN_name.py`: its
self-check, templated cells and `SPEC`) and its line below. Everything that lists lessons
derives from this table: `start(N)`, the titles, the self-checks, the templated cells, the
replays' driven nodes, the progress records and the hub's progress page. Importing it imports
neither rclpy nor mujoco (the hub's progress service imports it): a check imports those
inside its function.
"""

from __future__ import annotations

from importlib import import_module

from .spec import Check, LessonSpec, LessonView, check

__all__ = [
    "LESSONS",
    "NUMBERS",
    "TITLES",
    "Check",
    "LessonSpec",
    "check",
    "lesson_spec",
    "run_checks",
]


def _table(*modules: str) -> tuple[LessonSpec, ...]:
    """Return the SPEC of each lesson module named, checked against its name (`l07_...`)."""
    specs = tuple(import_module(f"{__name__}.{name}").SPEC for name in modules)
    for name, spec in zip(modules, specs, strict=True):
        if name[1:] != spec.notebook.removesuffix(".ipynb") or int(name[1:3]) != spec.number:
            raise ValueError(f"lesson module {name} holds lesson {spec.number} ({spec.notebook})")
    return specs


# One line per lesson, in order: the module in this folder that holds its SPEC.
LESSONS: tuple[LessonSpec, ...] = _table(
    "l01_setup_check",
    "l02_key_points",
    "l03_the_simulation",
    "l04_the_parameter_tests_package",
    "l05_run_the_node",
    "l06_check_parameters",
    "l07_move_the_robot",
    "l08_dump_parameters",
    "l09_load_yaml_at_startup",
    "l10_launch_files",
    "l11_beyond_the_tutorial",
)
NUMBERS: tuple[int, ...] = tuple(spec.number for spec in LESSONS)
TITLES: dict[int, str] = {spec.number: spec.title for spec in LESSONS}


def lesson_spec(number: int) -> LessonSpec:
    """Return lesson `number`'s entry; raise ValueError naming the lessons there are."""
    for spec in LESSONS:
        if spec.number == number:
            return spec
    raise ValueError(f"there are lessons {NUMBERS[0]} to {NUMBERS[-1]}, not {number}")


def run_checks(lesson: LessonView) -> list[Check]:
    """Return lesson `lesson.number`'s checks, run now."""
    return lesson_spec(lesson.number).check(lesson)
