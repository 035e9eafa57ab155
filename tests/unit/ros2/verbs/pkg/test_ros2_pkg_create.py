"""`ros2 pkg create` against the real ros2pkg 0.32.2: printed lines, exit code, every file."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from course_lib.ros2.command.commands import run_collected

GOLDEN = Path(__file__).resolve().parents[4] / "golden" / "pkg_create" / "cases.json"
CASES = {case["case"]: case for case in json.loads(GOLDEN.read_text())}
# A C++ library and a plain cmake package need templates the course does not offer: it says so.
NOT_OFFERED = {"cmake_library", "plain_cmake"}


def _tree(root: Path) -> tuple[dict[str, str], list[str]]:
    files = {str(p.relative_to(root)): p.read_text() for p in root.rglob("*") if p.is_file()}
    return files, sorted(str(p.relative_to(root)) for p in root.rglob("*") if p.is_dir())


def _run(case: dict[str, Any], folder: Path, monkeypatch: pytest.MonkeyPatch) -> Any:
    monkeypatch.setenv("HOME", str(folder))  # no git config: the maintainer is <user>@todo.todo
    monkeypatch.delenv("GIT_CONFIG_GLOBAL", raising=False)
    monkeypatch.setattr("getpass.getuser", lambda: "learner")
    work = folder / "work"
    work.mkdir()
    if case["case"] == "already_exists":
        (work / "my_package").mkdir()
    return run_collected(["pkg", "create", *case["args"]], cwd=str(work)), work


@pytest.mark.parametrize("name", sorted(set(CASES) - NOT_OFFERED))
def test_pkg_create_matches_ros2pkg(
    name: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    case = CASES[name]
    result, work = _run(case, tmp_path, monkeypatch)
    assert result.stdout.replace(str(work), "<cwd>") == case["stdout"]
    assert result.stderr == case["stderr"]
    assert result.exit_code == case["exit"]
    files, dirs = _tree(work)
    assert sorted(files) == sorted(case["files"])
    for path, text in case["files"].items():
        assert files[path] == text, path
    assert dirs == case["dirs"]


@pytest.mark.parametrize("name", sorted(NOT_OFFERED))
def test_pkg_create_says_what_it_does_not_offer(
    name: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    result, work = _run(CASES[name], tmp_path, monkeypatch)
    assert result.exit_code == 1 and not result.stdout
    assert result.stderr.count("\n") == 1 and "--build-type ament_python" in result.stderr
    assert not any(work.iterdir())
