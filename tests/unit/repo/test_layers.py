"""course_lib's layout: layers that only point down, a short root, folders one can take in."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[3]
PACKAGE = REPO / "course_lib"
MAX_ROOT_MODULES = 4
MAX_FOLDER_MODULES = 15
MAX_MODULE_LINES = 400
# The lesson catalogue's rows (lessons/catalogue/lNN_name.py): one per lesson, however many
# lessons the course has; they do not crowd their folder.
LESSON_ROW = re.compile(r"l\d\d_\w+\.py")


def test_imports_point_down_the_layers() -> None:
    """The import-linter contract of pyproject.toml, as `make lint` runs it.

    In a process of its own: import-linter configures logging with dictConfig, which disables
    every logger that exists (course_lib's, imported by the other tests of this worker) and
    closes pytest's handlers, so a later test's caplog saw nothing.
    """
    run = "from importlinter.cli import lint_imports_command; lint_imports_command()"
    args = ["--config", str(REPO / "pyproject.toml"), "--no-cache"]
    done = subprocess.run(
        [sys.executable, "-c", run, *args], capture_output=True, text=True, check=False
    )
    assert done.returncode == 0, done.stdout + done.stderr


def test_the_package_root_holds_only_its_doors() -> None:
    modules = sorted(p.name for p in PACKAGE.glob("*.py"))
    assert len(modules) <= MAX_ROOT_MODULES, modules


def crowded_folders(package: Path) -> dict[str, int]:
    """Return the folders of `package` with more than MAX_FOLDER_MODULES modules (rows aside)."""
    return {
        str(folder.relative_to(package.parent)): count
        for folder in [package, *(p for p in package.rglob("*") if p.is_dir())]
        if (count := sum(not LESSON_ROW.fullmatch(p.name) for p in folder.glob("*.py")))
        > MAX_FOLDER_MODULES
    }


def long_modules(package: Path) -> dict[str, int]:
    """Return the modules of `package` longer than MAX_MODULE_LINES lines."""
    return {
        str(path.relative_to(package.parent)): lines
        for path in package.rglob("*.py")
        if (lines := len(path.read_text(encoding="utf-8").splitlines())) > MAX_MODULE_LINES
    }


def test_no_folder_holds_more_than_fifteen_modules() -> None:
    assert crowded_folders(PACKAGE) == {}


def test_a_crowded_folder_is_found_and_lesson_rows_are_not_counted(tmp_path: Path) -> None:
    package = tmp_path / "pkg"
    (package / "many").mkdir(parents=True)
    (package / "rows").mkdir()
    for n in range(MAX_FOLDER_MODULES + 1):
        (package / "many" / f"m{n}.py").write_text("")
        (package / "rows" / f"l{n:02d}_lesson.py").write_text("")
    assert crowded_folders(package) == {"pkg/many": MAX_FOLDER_MODULES + 1}


def test_no_module_is_longer_than_four_hundred_lines() -> None:
    assert long_modules(PACKAGE) == {}


def test_a_long_module_is_found(tmp_path: Path) -> None:
    (tmp_path / "pkg").mkdir()
    (tmp_path / "pkg" / "long.py").write_text("x = 1\n" * (MAX_MODULE_LINES + 1))
    (tmp_path / "pkg" / "short.py").write_text("x = 1\n" * MAX_MODULE_LINES)
    assert long_modules(tmp_path / "pkg") == {"pkg/long.py": MAX_MODULE_LINES + 1}
