"""`make notebooks`: re-execute every lesson in place to refresh its stored outputs.

The configuration is checked first (a broken config/ runs nothing), and the cells that state a
configured value are rendered from it (course_lib.lessons.texts). Each notebook then runs top to
bottom in a fresh kernel (its own ROS domain, the test environment), and volatile parts are
removed so a second run changes nothing: execution metadata and widget state are dropped, the
sanitize rules of tests/nbval_sanitize.cfg are applied to text outputs, and cells tagged
`nbval-ignore-output` (3D view, widgets, live plots) keep their stored outputs when their source
and the settings the notebook was made with did not change (`--all` refreshes those too). A
cell's stored outputs are found by its cell id, never by its source: two cells may hold the
same code (lesson 11 runs `travel.check()` twice) and must each keep their own output.
Each lesson runs as a learner's first run: the exercises' attempt counts kept in `my_files/`
(yours, if you took the lessons in this clone) are set aside meanwhile and put back after.
"""

from __future__ import annotations

import argparse
import configparser
import contextlib
import copy
import os
import re
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from ..config.course import CourseSettings
from ..core.files.live_outputs import scrub_live_outputs
from ..core.paths import CONFIG_DIR_ENV, NOTEBOOKS_DIR, REPO_ROOT
from ..lessons.files import LEARNER_DIR
from ..lessons.skills.attempts import ATTEMPTS_FILE
from ..lessons.texts import METADATA_KEY, render_cells

__all__ = [
    "OUTPUT_ENV",
    "clean_notebook",
    "first_attempts",
    "refresh_notebook",
    "refresh_notebooks",
    "sanitize_rules",
]

# The environment the stored outputs are made in (`make notebooks`) and checked in (`make test`),
# so that they never depend on the machine.
OUTPUT_ENV = {
    "RCUTILS_COLORIZED_OUTPUT": "0",
    "PYTHONHASHSEED": "0",
    "IPYKERNEL_CELL_NAME": "<IPY-INPUT>",
    "PYDEVD_DISABLE_FILE_VALIDATION": "1",
}
SANITIZE_FILE = REPO_ROOT / "tests" / "nbval_sanitize.cfg"
IGNORE_TAG = "nbval-ignore-output"


def sanitize_rules(path: Path = SANITIZE_FILE) -> list[tuple[re.Pattern[str], str]]:
    """Return the (regex, replacement) pairs of the sanitize file, in order."""
    parser = configparser.ConfigParser(interpolation=None)
    parser.read(path)
    return [(re.compile(parser[s]["regex"]), parser[s]["replace"]) for s in parser.sections()]


def _sanitize(text: str, rules: list[tuple[re.Pattern[str], str]]) -> str:
    for regex, replacement in rules:
        text = regex.sub(replacement, text)
    return text


def _clean_output(output: Any, rules: list[tuple[re.Pattern[str], str]]) -> Any:
    if output.get("output_type") == "stream":
        output["text"] = _sanitize(output["text"], rules)
    for kind in ("text/plain", "text/html"):
        data = output.get("data", {})
        if isinstance(data.get(kind), str):
            data[kind] = _sanitize(data[kind], rules)
    if output.get("output_type") == "execute_result":
        output["execution_count"] = output.get("execution_count")
    if output.get("output_type") in ("display_data", "execute_result"):
        output.setdefault("metadata", {})  # required by the notebook format
    return output


def clean_notebook(nb: Any, old: Any | None, *, keep_live: bool = True) -> Any:
    """Strip volatile metadata; keep old outputs of unchanged live cells (when `keep_live`)."""
    rules = sanitize_rules()
    if old is not None and old.metadata.get(METADATA_KEY) != nb.metadata.get(METADATA_KEY):
        keep_live = False  # made with other settings: a kept verdict or hint would be stale
    nb.metadata.pop("widgets", None)
    nb.metadata.get("kernelspec", {}).pop("env", None)
    previous = {}
    if old is not None:
        previous = {c.get("id"): c for c in old.cells if c.cell_type == "code" and c.get("id")}
    for cell in nb.cells:
        cell.metadata.pop("execution", None)
        if cell.cell_type != "code":
            continue
        before = previous.get(cell.get("id"))
        if before is not None and before.source != cell.source:
            before = None  # the cell was edited: its old output no longer belongs to it
        live = IGNORE_TAG in cell.metadata.get("tags", [])
        if keep_live and live and before is not None and before.outputs:
            cell.outputs = copy.deepcopy(before.outputs)
            for output in cell.outputs:  # the kept result now shows this run's count
                if output.get("output_type") == "execute_result":
                    output["execution_count"] = cell.execution_count
        cell.outputs = [_clean_output(o, rules) for o in cell.outputs]
    if scrub_live_outputs(nb):  # a stored 3D view or widget would only show an error reopened
        import nbformat

        for cell in nb.cells:
            if cell.cell_type == "code":
                cell.outputs = [nbformat.from_dict(o) for o in cell.outputs]
    return nb


@contextlib.contextmanager
def first_attempts(folder: Path = LEARNER_DIR) -> Iterator[None]:
    """Run the body with no exercise attempts counted in `folder`; put the counts back after."""
    attempts = folder / ATTEMPTS_FILE
    try:
        kept: bytes | None = attempts.read_bytes()
    except FileNotFoundError:
        kept = None
    attempts.unlink(missing_ok=True)
    try:
        yield
    finally:
        if kept is None:
            attempts.unlink(missing_ok=True)
        else:
            attempts.write_bytes(kept)


def refresh_notebook(
    path: Path, settings: CourseSettings, *, keep_live: bool = True, timeout: int = 180
) -> float:
    """Render `path`'s configured cells, execute it in place; return the wall time in seconds."""
    import nbformat
    from nbclient import NotebookClient

    old = nbformat.read(path, as_version=4)
    nb = copy.deepcopy(old)
    render_cells(path.name, nb, settings)
    for cell in nb.cells:
        if cell.cell_type == "code":
            cell.outputs, cell.execution_count = [], None
    started = time.monotonic()
    client = NotebookClient(
        nb,
        timeout=timeout,
        kernel_name="python3",
        resources={"metadata": {"path": str(path.parent)}},
        record_timing=False,
    )
    with first_attempts():
        client.execute()
    clean_notebook(nb, old, keep_live=keep_live)
    nbformat.validate(nb)  # never store a notebook JupyterLab would flag as invalid
    text = nbformat.writes(nb) + "\n"
    if path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")
    return time.monotonic() - started


def _options(extra: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="make notebooks ARGS=...",
        description="Render the lessons' configured cells from config/course.yaml, re-execute "
        "the lessons and store their outputs (all lessons, or those named).",
    )
    parser.add_argument("names", nargs="*", help="notebooks, e.g. 07_move_the_robot.ipynb")
    parser.add_argument(
        "--all", action="store_true", help="refresh live cells (3D view, widgets) too"
    )
    parser.add_argument("--config", type=Path, help="another folder of instructor YAML")
    return parser.parse_args(extra)


def refresh_notebooks(extra: list[str]) -> int:
    """Re-execute the notebooks (all, or those named in `extra`); return an exit code."""
    from .config_check import require_valid_config

    options = _options(extra)
    if options.config is not None:
        os.environ[CONFIG_DIR_ENV] = str(options.config.resolve())  # the kernels read it too
    settings = require_valid_config(show_notes=False)["course.yaml"]  # broken: nothing runs
    names = options.names
    paths = [Path(n) if os.sep in n else NOTEBOOKS_DIR / n for n in names] or sorted(
        NOTEBOOKS_DIR.glob("[0-9][0-9]_*.ipynb")
    )
    os.environ.update(OUTPUT_ENV)
    failed = 0
    for path in paths:
        try:
            seconds = refresh_notebook(path, settings, keep_live=not options.all)
        except Exception as err:  # a failing cell: report it and go on with the others
            failed += 1
            print(f"FAILED {path.name}: {type(err).__name__}: {str(err)[-2000:]}", file=sys.stderr)
            continue
        print(f"{path.name}: {seconds:.1f} s")
    return 1 if failed else 0
