"""course_lib's layout: layers that only point down, a short root, folders one can take in."""

from __future__ import annotations

from pathlib import Path

from importlinter.cli import lint_imports

REPO = Path(__file__).resolve().parents[3]
PACKAGE = REPO / "course_lib"
MAX_ROOT_MODULES = 4
MAX_FOLDER_MODULES = 15


def test_imports_point_down_the_layers(capsys) -> None:  # type: ignore[no-untyped-def]
    """The import-linter contract of pyproject.toml, as `make lint` runs it."""
    code = lint_imports(config_filename=str(REPO / "pyproject.toml"), no_cache=True, no_logo=True)
    assert code == 0, capsys.readouterr().out


def test_the_package_root_holds_only_its_doors() -> None:
    modules = sorted(p.name for p in PACKAGE.glob("*.py"))
    assert len(modules) <= MAX_ROOT_MODULES, modules


def test_no_folder_holds_more_than_fifteen_modules() -> None:
    crowded = {
        str(folder.relative_to(REPO)): count
        for folder in [PACKAGE, *(p for p in PACKAGE.rglob("*") if p.is_dir())]
        if (count := len(list(folder.glob("*.py")))) > MAX_FOLDER_MODULES
    }
    assert not crowded, crowded
