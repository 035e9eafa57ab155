"""`make lab`: the command line it runs, and how terminals find its domain."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from course_lib.core.paths import runtime_dir
from course_lib.lab import jupyterlab as lab
from course_lib.processes import lab_markers


def test_lab_listens_on_loopback_and_keeps_ros2_on_terminal_path() -> None:
    argv = lab.lab_argv(["--no-browser"])
    assert "--ServerApp.ip=127.0.0.1" in argv
    settings = next(a for a in argv if a.startswith("--ServerApp.terminado_settings="))
    shell_command = json.loads(settings.split("=", 1)[1])["shell_command"]
    assert "-l" not in shell_command and "--login" not in shell_command
    assert argv[-1] == "--no-browser"
    # the address printed (and opened) is lesson 1's, not the Launcher's
    assert f"--LabApp.default_url=/lab/tree/{lab.FIRST_LESSON}" in argv


def test_the_course_lab_settings_start_a_shut_down_notebooks_kernel_without_asking() -> None:
    option = next(a for a in lab.course_server_options() if "app_settings_dir" in a)
    folder = option.split("=", 1)[1]
    overrides = json.loads((Path(folder) / "overrides.json").read_text())
    assert overrides["@jupyterlab/notebook-extension:tracker"]["autoStartDefaultKernel"] is True


def test_the_course_lab_saves_open_notebooks_every_20_seconds() -> None:
    """What a killed server can lose of a learner's edits (book/guides/getting-started.md)."""
    option = next(a for a in lab.course_server_options() if "app_settings_dir" in a)
    overrides = json.loads((Path(option.split("=", 1)[1]) / "overrides.json").read_text())
    saving = overrides["@jupyterlab/docmanager-extension:plugin"]
    assert saving == {"autosave": True, "autosaveInterval": 20}


@pytest.fixture
def markers() -> list:
    made: list = []
    yield made
    for marker in made:
        marker.unlink(missing_ok=True)


def test_terminals_use_the_running_labs_domain(markers: list) -> None:
    marker = runtime_dir() / f"lab-{os.getpid()}.domain"
    marker.write_text("77")
    markers.append(marker)
    assert lab_markers.running_lab_domain() == "77"


def test_a_killed_labs_marker_is_ignored_and_removed(markers: list) -> None:
    dead = subprocess.run(
        [sys.executable, "-c", "import os; print(os.getpid())"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()
    marker = runtime_dir() / f"lab-{dead}.domain"
    marker.write_text("78")
    markers.append(marker)
    assert lab_markers.running_lab_domain() != "78"
    assert not marker.exists()


def test_a_legacy_header_fits_its_message_or_is_refused() -> None:
    from course_lib.lab.kernel_socket import legacy_header_fits

    header = b"".join(n.to_bytes(4, "big") for n in (2, 12, 14))  # 2 parts, their offsets
    two_parts = header + b"{}[]"
    assert legacy_header_fits(two_parts)
    assert not legacy_header_fits((6).to_bytes(8, "little") + bytes(56))  # 100,663,296 parts
    assert not legacy_header_fits(b"\x00\x00")
    assert not legacy_header_fits((0).to_bytes(4, "big") + bytes(8))
    assert not legacy_header_fits((-1).to_bytes(4, "big", signed=True) + bytes(8))
