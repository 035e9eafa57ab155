"""course_lib's layout: layers that only point down, a short root, folders one can take in."""

from __future__ import annotations

import re
from pathlib import Path

from importlinter.cli import lint_imports

REPO = Path(__file__).resolve().parents[3]
PACKAGE = REPO / "course_lib"
MAX_ROOT_MODULES = 4
MAX_FOLDER_MODULES = 15
MAX_MODULE_LINES = 400
# The lesson catalogue's rows (lessons/catalogue/lNN_name.py): one per lesson, however many
# lessons the course has; they do not crowd their folder.
LESSON_ROW = re.compile(r"l\d\d_\w+\.py")


def test_imports_point_down_the_layers(capsys) -> None:  # type: ignore[no-untyped-def]
    """The import-linter contract of pyproject.toml, as `make lint` runs it."""
    code = lint_imports(config_filename=str(REPO / "pyproject.toml"), no_cache=True, no_logo=True)
    assert code == 0, capsys.readouterr().out


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
