"""An instructor's broken YAML: the first cell names file, line and key; nothing is overwritten."""

from __future__ import annotations

import hashlib
from pathlib import Path

import pytest

from course_lib.core.paths import CONFIG_DIR

pytestmark = [pytest.mark.ros]

GOOD = (CONFIG_DIR / "simulation.yaml").read_text()

CASES = {
    # name: (broken text, key, words the explanation must use)
    "syntax": (
        GOOD.replace("  y_m: 0.0", "  y_m: [0.0"),
        "(syntax)",
        "not valid YAML",
    ),
    "unknown_key": (
        GOOD.replace("  yaw_deg: 0.0", "  yaw_degrees: 0.0"),
        "start_pose.yaw_degrees",
        "unknown key",
    ),
    "wrong_type": (
        GOOD.replace("  odom_hz: 50.0", "  odom_hz: fast"),
        "rates.odom_hz",
        "expected a number",
    ),
}


def _digest(folder: Path) -> dict[str, str]:
    return {
        str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(folder.rglob("*"))
        if p.is_file()
    }


def _line_of(text: str, needle: str) -> int:
    return next(n for n, line in enumerate(text.splitlines(), 1) if needle in line)


def test_broken_instructor_yaml_is_explained(start_kernel, tmp_path: Path) -> None:
    config_before = _digest(CONFIG_DIR)
    kernel = start_kernel()
    for name, (text, key, words) in CASES.items():
        assert text != GOOD, f"case {name} did not change the file"
        folder = tmp_path / name
        folder.mkdir()
        path = folder / "simulation.yaml"
        path.write_text(text)
        line = _line_of(text, "[0.0" if name == "syntax" else key.rsplit(".", 1)[-1] + ":")
        out = kernel.run(
            "from course_lib.notebook import start_world\n"
            f"world = start_world(show=True, config={str(path)!r})"
        )
        assert "ConfigError" in out.error, out.everything
        assert f"{path}, line {line}: {key}: {words}" in out.error, out.everything
        assert "Try: " in out.error, out.everything
        assert path.read_text() == text, f"{name}: the broken file was changed"
        started = kernel.ok(
            "from course_lib.session.session import get_session\n"
            "print(len(get_session().children))"
        ).text
        assert started.strip() == "0", f"{name}: processes started despite the error"
    assert _digest(CONFIG_DIR) == config_before, "config/ was changed"
