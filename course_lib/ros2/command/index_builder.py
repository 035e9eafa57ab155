"""Gather the verb modules' declarations into `verb_index.py`, the table a terminal reads.

Every `ros2` command and verb is declared once, beside its code (`command`, `@verb`,
`@command_verb`, `@raw_command` of course_lib/ros2/verbkit/registry.py). Importing every verb
module costs about 100 ms (rclpy among them), so a terminal's `ros2` never does: it reads
`verb_index.py`, which this module writes. After adding or changing a verb, run::

    python -m course_lib.ros2.command.index_builder

tests/unit/ros2/command/test_verb_registry.py fails (naming that command) while they differ.
"""

from __future__ import annotations

import importlib
import json
import pkgutil
import sys
from pathlib import Path

from ..verbkit.registry import (
    CommandDeclaration,
    VerbDeclaration,
    declared_commands,
    declared_verbs,
)

__all__ = ["INDEX_PATH", "REWRITE", "declarations", "index_text", "verb_modules", "write_index"]

INDEX_PATH = Path(__file__).with_name("verb_index.py")
REWRITE = "python -m course_lib.ros2.command.index_builder"
_VERBS_PACKAGE = "course_lib.ros2.verbs"

_HEADER = (
    '"""The `ros2` commands and verbs of course_lib/ros2/verbs (generated: do not edit).\n'
    "\n"
    "Written from the declarations beside each verb (course_lib/ros2/verbkit/registry.py) by\n"
    f"`{REWRITE}`, so that a terminal's `ros2` knows every\n"
    "verb without importing it; tests/unit/ros2/command/test_verb_registry.py fails while the\n"
    'two differ.\n"""\n\n'
)


def verb_modules() -> list[str]:
    """Return the name of every module under course_lib.ros2.verbs (packages included)."""
    package = importlib.import_module(_VERBS_PACKAGE)
    names = [_VERBS_PACKAGE]
    for info in pkgutil.walk_packages(package.__path__, _VERBS_PACKAGE + "."):
        names.append(info.name)
    return sorted(names)


def declarations() -> tuple[dict[str, CommandDeclaration], dict[tuple[str, str], VerbDeclaration]]:
    """Import every verb module and return what they declare: commands, then verbs."""
    for name in verb_modules():
        importlib.import_module(name)
    return declared_commands(), declared_verbs()


def _literal(value: object) -> str:
    if isinstance(value, str):
        return json.dumps(value)  # double quotes, as the formatter writes them
    return repr(value)


def _entry(key: str, fields: tuple[object, ...]) -> str:
    inner = "".join(f"        {_literal(f)},\n" for f in fields)
    return f"    {key}: (\n{inner}    ),\n"


def index_text() -> str:
    """Return the text of verb_index.py for the declarations of every verb module."""
    commands, verbs = declarations()
    lines = [_HEADER, "# name: (help line, options builder before its verb, raw handler)\n"]
    lines.append("COMMANDS = {\n")
    for name in sorted(commands):
        c = commands[name]
        lines.append(_entry(_literal(name), (c.doc, c.options, c.raw)))
    lines.append("}\n")
    lines.append(
        "# (command, verb): (help line, handler, arguments builder, uses the ROS graph);\n"
        '# verb "": the command is itself the verb (`ros2 run`)\n'
    )
    lines.append("VERBS = {\n")
    for key in sorted(verbs):
        v = verbs[key]
        fields = (v.doc, v.handler, v.arguments, v.graph)
        lines.append(_entry(f"({_literal(key[0])}, {_literal(key[1])})", fields))
    lines.append("}\n")
    return "".join(lines)


def write_index() -> Path:
    """Write verb_index.py from the verb modules' declarations; return its path."""
    INDEX_PATH.write_text(index_text())
    return INDEX_PATH


if __name__ == "__main__":
    print(write_index())
    sys.exit(0)
