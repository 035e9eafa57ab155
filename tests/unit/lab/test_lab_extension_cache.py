"""The course's lab extension is served under a name that changes with its content.

JupyterLab serves an extension's static files as immutable for a year: a learner's browser
kept the old plugin after the course was updated in place (a hub rebuilt, a `git pull`). The
file is named by its content's digest, which package.json's `load` names; an edit without a
new name fails here.
"""

from __future__ import annotations

import hashlib
import json

from course_lib.core.paths import PACKAGE_DIR

EXTENSION = PACKAGE_DIR / "lab_extensions" / "@ros2-course" / "lab"


def test_the_extensions_script_is_named_by_its_content() -> None:
    load = json.loads((EXTENSION / "package.json").read_text())["jupyterlab"]["_build"]["load"]
    script = EXTENSION / load
    digest = hashlib.sha256(script.read_bytes()).hexdigest()[:12]
    assert script.name == f"remoteEntry.{digest}.js", (
        f"{load} was edited: rename it remoteEntry.{digest}.js and name that in package.json"
    )
    assert [p.name for p in script.parent.iterdir()] == [script.name], "an old script is left"
