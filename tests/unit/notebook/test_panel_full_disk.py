"""The parameter panel's Save into a full disk says so in its log, in one line and a Try."""

from __future__ import annotations

import errno
from pathlib import Path

import pytest

from course_lib.core.files.atomic_files import FileSaveError
from course_lib.notebook.widgets.param_panel import ParameterPanel


class _Log:
    def __init__(self) -> None:
        self.text = ""

    def append_stdout(self, text: str) -> None:
        self.text += text


def _full_disk(path: Path | None = None) -> Path:
    raise FileSaveError(Path("my_files/panel_params.yaml"), OSError(errno.ENOSPC, "full"))


def test_save_clicked_on_a_full_disk_says_not_saved_and_keeps_the_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "my_files").mkdir()
    (tmp_path / "my_files" / "panel_params.yaml").write_text("old\n")
    panel = ParameterPanel.__new__(ParameterPanel)  # its Save only: no node, no widgets
    panel.log = _Log()
    monkeypatch.setattr(panel, "save", _full_disk)
    panel._save_clicked()
    assert panel.log.text == (
        "Not saved (my_files/panel_params.yaml): the disk is full. The file as it was before "
        "is kept.\nTry: free some space (old replays in my_files/replays/, for example), then "
        "run the cell again.\n"
    )
