"""`make lab` stops at once, in one sentence, on a machine the Jazzy wheels do not cover."""

from __future__ import annotations

import importlib.util
from pathlib import Path
from types import ModuleType

import pytest

SCRIPT = Path(__file__).resolve().parents[3] / "scripts" / "check_platform.py"


def _load() -> ModuleType:
    spec = importlib.util.spec_from_file_location("check_platform", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_this_machine_is_supported() -> None:
    assert _load().main() == 0


@pytest.mark.parametrize("version", [(3, 11), (3, 12)])
def test_the_pythons_ci_proves_are_accepted(
    monkeypatch: pytest.MonkeyPatch, version: tuple[int, int]
) -> None:
    module = _load()
    monkeypatch.setattr(module.sys, "version_info", (*version, 0, "final", 0))
    assert module.main() == 0


def test_claims_agree_everywhere() -> None:
    """README, the getting-started guide, pyproject and environment.txt claim what the check
    accepts: 3.11 and 3.12."""
    root = SCRIPT.parents[1]
    for page in ("README.md", "book/guides/getting-started.md"):
        text = (root / page).read_text(encoding="utf-8")
        assert "CPython 3.11 or 3.12" in text and "3.10" not in text, page
    assert 'requires-python = ">=3.11,<3.13"' in (root / "pyproject.toml").read_text()
    header = (root / "environment.txt").read_text().split("\n\n", 1)[0]
    assert "CPython 3.11-3.12" in header and "3.10-" not in header


@pytest.mark.parametrize(
    ("system", "machine", "version", "says"),
    [
        ("Darwin", "arm64", (3, 11), "this machine is Darwin arm64"),
        ("Linux", "x86_64", (3, 13), "is CPython 3.13"),
        ("Linux", "aarch64", (3, 9), "Linux aarch64 and"),
        ("Linux", "x86_64", (3, 10), "is CPython 3.10"),  # numpy 2.4.6 has no 3.10 wheel
    ],
)
def test_unsupported_platforms_get_one_clear_sentence(
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
    system: str,
    machine: str,
    version: tuple[int, int],
    says: str,
) -> None:
    module = _load()
    monkeypatch.setattr(module.platform, "system", lambda: system)
    monkeypatch.setattr(module.platform, "machine", lambda: machine)
    monkeypatch.setattr(module.sys, "version_info", (*version, 0, "final", 0))
    assert module.main() == 1
    err = capsys.readouterr().err
    assert err.startswith("The course runs on Linux x86_64 with CPython 3.11 or 3.12")
    assert says in err
    assert "Try: make lab PYTHON=python3.11" in err


@pytest.mark.parametrize(
    ("absent", "says"),
    [
        ({"g++", "c++"}, "sudo apt-get install g++"),
        ({"make"}, "sudo apt-get install make"),
        ({"g++", "c++", "cc", "make"}, "sudo apt-get install g++ make"),
    ],
)
def test_missing_compiler_gets_one_sentence_before_any_build(
    monkeypatch: pytest.MonkeyPatch,
    capsys: pytest.CaptureFixture[str],
    absent: set[str],
    says: str,
) -> None:
    module = _load()
    which = module.shutil.which
    monkeypatch.setattr(
        module.shutil, "which", lambda name: None if name in absent else which(name)
    )
    assert module.main() == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("The course builds the tf2_msgs messages")
    assert err.rstrip().endswith(says)


def test_missing_python_headers_name_the_dev_package(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    module = _load()
    monkeypatch.setattr(module.sysconfig, "get_paths", lambda: {"include": str(tmp_path)})
    assert module.main() == 1
    assert "python3." in capsys.readouterr().err.split("install ")[-1]


def test_workspace_build_stops_with_the_same_sentence_without_a_compiler(
    tmp_path: Path,
) -> None:
    import os
    import subprocess
    import sys

    # A PATH holding only python: no c++, no make.
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    (bin_dir / "python").symlink_to(sys.executable)
    done = subprocess.run(
        [str(bin_dir / "python"), "-m", "course_lib", "build", "--workspace", str(tmp_path)],
        cwd=SCRIPT.parents[1],
        env={**os.environ, "PATH": str(bin_dir)},
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )
    assert done.returncode == 1
    assert done.stderr.startswith("The course builds the tf2_msgs messages")
    assert "sudo apt-get install g++ make" in done.stderr
    assert not (tmp_path / "build").exists()  # nothing was built
