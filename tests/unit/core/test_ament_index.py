"""The one ament-index reader follows ament_index_python's rules on the prefixes it is given."""

from __future__ import annotations

from pathlib import Path

import pytest

from course_lib.core import ament_index


def _index(root: Path, kind: str, name: str, content: str = "") -> Path:
    folder = root / ament_index.INDEX / kind
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_text(content)
    return root


def test_first_prefix_wins_and_dot_files_and_folders_are_no_resources(tmp_path: Path) -> None:
    mine = _index(tmp_path / "mine", "packages", "demo", "mine")
    theirs = _index(tmp_path / "theirs", "packages", "demo", "theirs")
    _index(theirs, "packages", ".hidden")
    (theirs / ament_index.INDEX / "packages" / "sub").mkdir()
    assert ament_index.resources("packages", [mine, theirs]) == {"demo": mine}
    assert ament_index.resource_prefix("packages", "demo", [theirs, mine]) == theirs
    assert ament_index.resource("packages", "demo", [mine, theirs]) == "mine"
    with pytest.raises(LookupError):
        ament_index.resource("packages", "sub", [theirs])


def test_prefix_path_tells_unset_from_empty() -> None:
    assert ament_index.prefix_path({}) is None
    assert ament_index.prefix_path({"AMENT_PREFIX_PATH": ""}) == []
    assert ament_index.prefix_path({"AMENT_PREFIX_PATH": "/a::/b"}) == [Path("/a"), Path("/b")]
