"""What a cell shows when it fails: a course error as its two lines, and the usual slips of
a new or restarted kernel as what to run, never as a traceback.

A kernel that died or was restarted (a crash, the out-of-memory killer, Kernel > Restart)
forgets the lesson: the next cell that uses `lesson`, `world` or `plot` fails with a NameError,
and `%ros2` with "Line magic function not found". Both are said in the learner's terms: which
cell of this notebook defines the name (found in the notebook the kernel runs for, named by
Jupyter in JPY_SESSION_NAME), or that the lesson's first cell loads `%ros2`. Any other error
keeps IPython's own traceback. The course's kernel loads the hints as it starts
(kernel_launcher); `start(N)` installs them with the course errors (IPython keeps one handler).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Any

from ..core.errors import CourseError

__all__ = ["defining_cell", "hint_for", "install", "load_ipython_extension", "show_error"]

SESSION_ENV = "JPY_SESSION_NAME"  # Jupyter's: the notebook a kernel was started for
_MISSING_MAGIC = "Line magic function `%ros2` not found"
_RESTARTED = "this kernel has not run it since it started (a new or restarted kernel)"


def _code_cells(notebook: Path) -> list[str]:
    import json  # here: the kernel loads this module as it starts, and seldom needs it

    try:
        cells = json.loads(notebook.read_text(encoding="utf-8")).get("cells", [])
    except (OSError, ValueError, AttributeError):
        return []
    return [
        "".join(c.get("source", "")) if isinstance(c.get("source"), list) else c.get("source", "")
        for c in cells
        if isinstance(c, dict) and c.get("cell_type") == "code"
    ]


def _assigned(source: str) -> dict[str, int]:
    """Return the names a cell's Python assigns, defines or imports, each with the line (from
    1) where it first does (its magic lines left out)."""
    import ast

    python = "\n".join(
        "" if line.lstrip().startswith(("%", "!")) else line for line in source.splitlines()
    )
    try:
        tree = ast.parse(python)
    except SyntaxError:
        return {}
    found: list[tuple[int, str]] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            found.append((node.lineno, node.id))
        elif isinstance(node, ast.Import | ast.ImportFrom):
            found += [(node.lineno, (a.asname or a.name).split(".")[0]) for a in node.names]
        elif isinstance(node, ast.FunctionDef | ast.ClassDef):
            found.append((node.lineno, node.name))
    lines: dict[str, int] = {}
    for line, name in sorted(found):
        lines.setdefault(name, line)
    return lines


def defining_cell(notebook: Path, name: str) -> str | None:
    """Return the line of `notebook`'s first code cell that defines `name` (None: none)."""
    for source in _code_cells(notebook):
        line = _assigned(source).get(name)
        if line is not None:
            return source.splitlines()[line - 1].strip()
    return None


def _first_cell(notebook: Path) -> str | None:
    cells = [s.strip() for s in _code_cells(notebook) if s.strip()]
    return cells[0].splitlines()[-1] if cells else None


def hint_for(error: BaseException, notebook: Path | None) -> str | None:
    """Return what to say for `error` in a kernel running `notebook` (None: a real error)."""
    if notebook is None:
        return None
    first = _first_cell(notebook)
    if isinstance(error, NameError) and error.name:
        cell = defining_cell(notebook, error.name)
        if cell is None:
            return None  # not a name of this lesson: the learner's own slip, shown as usual
        return (
            f"NameError: `{error.name}` is defined by the cell `{cell}`: {_RESTARTED}.\n"
            f"Try: run the cells from the top (Run > Run All Cells), the first being `{first}`."
        )
    if _MISSING_MAGIC in str(error) and first is not None:
        return (
            f"`%ros2` is not loaded in this kernel: {_RESTARTED}.\n"
            f"Try: run the lesson's first cell, `{first}`, then this cell again."
        )
    return None


def _session_notebook() -> Path | None:
    named = os.environ.get(SESSION_ENV)
    return Path(named) if named and named.endswith(".ipynb") else None


def show_error(
    shell: Any, etype: type, value: BaseException, tb: Any, tb_offset: int | None = None
) -> None:
    """IPython's custom exception handler: a course error's lines, a restart's hint, or the
    traceback IPython would have shown."""
    if isinstance(value, CourseError):
        print(f"{etype.__name__}: {value}", file=sys.stderr)
        return
    hint = hint_for(value, _session_notebook())
    if hint is not None:
        print(hint, file=sys.stderr)
        return
    shell.showtraceback((etype, value, tb), tb_offset=tb_offset)


def install(shell: Any, *, course_errors: bool = True) -> None:
    """Make `shell` show cell errors this way: a new or restarted kernel's slips (NameError, a
    missing magic) and, with `course_errors`, course errors as their two lines."""
    from IPython.core.error import UsageError

    handled = (CourseError,) if course_errors else ()
    shell.set_custom_exc((*handled, NameError, UsageError), show_error)


def load_ipython_extension(shell: Any) -> None:
    """`%load_ext course_lib.notebook.cell_errors`, which the course's kernel does as it
    starts: the restart hints only; `start(N)` adds course errors (before it, a script's
    course error keeps its traceback, as it always had)."""
    install(shell, course_errors=False)
