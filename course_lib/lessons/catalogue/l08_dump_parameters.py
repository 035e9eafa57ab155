"""Lesson 8, dump parameters: the learner's dump is what `ros2 param dump` prints now."""

from __future__ import annotations

from .shared import written_in
from .spec import Check, LessonSpec, LessonView, check

__all__ = ["DUMP_NAME", "SPEC"]

# The learner's own file (the package's params file is never rewritten).
DUMP_NAME = "dump/param_vel_node.yaml"


def self_check(lesson: LessonView) -> list[Check]:
    """Return lesson 8's checks of the dump file in my_files/."""
    import yaml

    from ...ros2.api import nodes_and_params as api

    dump = lesson.learner_file(DUMP_NAME)
    try:
        if not written_in(lesson, dump):
            raise OSError("written by an earlier run")
        text = dump.read_text(encoding="utf-8")
        value = yaml.safe_load(text)["/param_vel_node"]["ros__parameters"]["velocity"]
    except (OSError, yaml.YAMLError, KeyError, TypeError):
        text, value = None, None
    live = api.ros2("param dump /param_vel_node").stdout
    return [
        check(
            f"my_files/{DUMP_NAME} holds /param_vel_node's ros__parameters",
            isinstance(value, float),
            "run the cell that redirects the dump into the file.",
        ),
        check(
            "the file is exactly what `ros2 param dump` prints now",
            live == text,
            "dump again into the file.",
        ),
    ]


SPEC = LessonSpec(8, "08_dump_parameters.ipynb", "Dump parameters", self_check)
