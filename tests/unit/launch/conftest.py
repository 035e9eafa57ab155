"""Fixtures of the launch unit tests: the fixture package as an ament prefix."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

_PREFIX_PY = Path(__file__).resolve().parents[2] / "fixtures" / "launch_pkg" / "prefix.py"


def load_prefix_module():  # type: ignore[no-untyped-def]
    """Import tests/fixtures/launch_pkg/prefix.py by path."""
    spec = importlib.util.spec_from_file_location("launch_fixture_prefix", _PREFIX_PY)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="session")
def fixture_prefix(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Return an ament prefix holding the fixture package `parameter_tests`."""
    return load_prefix_module().make_prefix(tmp_path_factory.mktemp("launch_prefix"))


@pytest.fixture
def ament_fixture(fixture_prefix: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """Put only the fixture prefix on AMENT_PREFIX_PATH for one test."""
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(fixture_prefix))
    return fixture_prefix
