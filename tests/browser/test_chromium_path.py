"""The browser tests find chromium on PATH, wherever it is installed (no browser started)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from browser_path import find_chromium


def _executable(folder: Path, name: str) -> Path:
    path = folder / name
    path.write_text("#!/bin/sh\n")
    path.chmod(0o755)
    return path


def test_finds_chromium_anywhere_on_path(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("CHROMIUM", raising=False)
    empty, bin_dir = tmp_path / "empty", tmp_path / "bin"
    empty.mkdir(), bin_dir.mkdir()
    browser = _executable(bin_dir, "chromium-browser")
    assert find_chromium(os.pathsep.join([str(empty), str(bin_dir)])) == str(browser)


def test_missing_chromium_is_none(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("CHROMIUM", raising=False)
    assert find_chromium(str(tmp_path)) is None


def test_chromium_variable_names_the_browser(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    browser = _executable(tmp_path, "my-chromium")
    monkeypatch.setenv("CHROMIUM", str(browser))
    assert find_chromium("") == str(browser)
