"""course_lib's types: mypy under pyproject.toml's [tool.mypy], as `make lint` runs it."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[3]
CONFIG = REPO / "pyproject.toml"
# A module of a strict layer and one of a basic one, each with the same two mistakes.
PROBE = 'def untyped(x):\n    return x\n\n\ncount: int = "one"\n'
STRICT_PROBE = "course_lib/core/probe.py"
BASIC_PROBE = "course_lib/lab/probe.py"
ERROR = re.compile(r"^(?P<path>\S+):(?P<line>\d+): error: .*\[(?P<code>[a-z-]+)\]$", re.MULTILINE)


def run_mypy(*targets: str, cwd: Path, cache: Path) -> tuple[int, str]:
    """Run mypy on `targets` from `cwd` under the repository's config; return (code, output).

    Its own cache folder: a cold, deterministic run that leaves nothing in the clone.
    """
    options = ["--config-file", str(CONFIG), "--cache-dir", str(cache)]
    done = subprocess.run(
        [sys.executable, "-m", "mypy", *options, *targets],
        cwd=cwd,
        capture_output=True,
        text=True,
        check=False,
    )
    return done.returncode, done.stdout + done.stderr


def test_course_lib_type_checks(tmp_path: Path) -> None:
    code, output = run_mypy("course_lib", cwd=REPO, cache=tmp_path / "cache")
    assert code == 0, output
    # a package named in an override that course_lib no longer imports: drop it from the list
    assert "unused section" not in output, output


def test_mypy_reports_a_wrong_module_at_its_layers_level(tmp_path: Path) -> None:
    """The config fails wrong code: the strict layers refuse an unannotated function too."""
    for probe in (STRICT_PROBE, BASIC_PROBE):
        module = tmp_path / "tree" / probe
        module.parent.mkdir(parents=True, exist_ok=True)
        for package in (module.parent, module.parent.parent):
            (package / "__init__.py").touch()
        module.write_text(PROBE)
    code, output = run_mypy(
        STRICT_PROBE, BASIC_PROBE, cwd=tmp_path / "tree", cache=tmp_path / "cache"
    )
    assert code == 1, output
    errors = {(m["path"], int(m["line"]), m["code"]) for m in ERROR.finditer(output)}
    assert errors == {
        (STRICT_PROBE, 1, "no-untyped-def"),
        (STRICT_PROBE, 5, "assignment"),
        (BASIC_PROBE, 5, "assignment"),
    }, output
