"""book/guides/architecture.md is true to the code: every path it names exists, and every folder of
course_lib (code or data) is named in it."""

from __future__ import annotations

import re
from pathlib import Path

from course_lib.core.paths import REPO_ROOT

DOC = REPO_ROOT / "book" / "guides" / "architecture.md"
PACKAGE = REPO_ROOT / "course_lib"
FILE_SUFFIXES = (".py", ".md", ".yaml", ".yml", ".json", ".toml", ".ipynb", ".xml", ".cmake")
CODE_SPAN = re.compile(r"`([^`\s]+)`")
PLACEHOLDER = re.compile(r"NN|<|\*|\{")
# The learner's folder (notebooks/my_files/, lessons/files.py) is made when a lesson first
# runs: a clone has none, so what the page says of it is not looked for.
LEARNERS = "my_files/"


def _named(text: str) -> list[str]:
    """Return the path-like code spans of `text`: a slash inside, or a file's suffix."""
    names = []
    for span in CODE_SPAN.findall(text):
        token = span.rstrip(".,;:)").split(":")[0]
        if PLACEHOLDER.search(token) or "://" in span or token.startswith(("/", "~")):
            continue  # a template, a URL or a ROS name (`/cmd_vel`)
        if "/" in token.rstrip("/") or token.endswith(FILE_SUFFIXES) or token.endswith("/"):
            names.append(token)
    return names


def _candidates(token: str) -> list[Path]:
    """Return where `token` may live: from the repository, from course_lib, as `module.attr`."""
    roots = [REPO_ROOT, PACKAGE]
    forms = [token]
    if not token.endswith(FILE_SUFFIXES) and not token.endswith("/"):
        parts = token.split(".")  # `sim/world/kinematics.DiffDrive.wheel_speeds`
        forms += [".".join(parts[:n]) + ".py" for n in range(1, len(parts) + 1)]
    return [root / form for root in roots for form in forms]


def _exists_somewhere(token: str) -> bool:
    """A bare `name/` or `name.py` names a folder or file of that name anywhere in the code."""
    name = token.rstrip("/")
    places = [PACKAGE, REPO_ROOT / "tests", REPO_ROOT / "book", REPO_ROOT / "config"]
    return any(
        any(p for p in place.rglob(name) if "__pycache__" not in p.parts) for place in places
    )


def _under_a_folder(token: str) -> bool:
    """A path said in its folder's paragraph: `command/table.py` for `ros2/command/table.py`."""
    tail = token.rstrip("/")
    return any(
        p.as_posix().endswith("/" + tail)
        for p in PACKAGE.rglob(tail.rsplit("/", 1)[-1])
        if "__pycache__" not in p.parts
    )


def missing_paths(text: str) -> list[str]:
    """Return the paths `text` names that exist nowhere."""
    missing = []
    for token in _named(text):
        if token.startswith(LEARNERS):
            continue
        if any(p.exists() for p in _candidates(token)) or _under_a_folder(token):
            continue
        if "/" not in token.rstrip("/") and _exists_somewhere(token):
            continue
        missing.append(token)
    return sorted(set(missing))


def unnamed_folders(text: str) -> list[str]:
    """Return the folders of course_lib whose name the text never gives as `name/`: its
    packages and the data folders at its root."""
    named = {t.rstrip("/").rsplit("/", 1)[-1] for t in _named(text) if t.endswith("/")}
    folders = {
        p.relative_to(PACKAGE).as_posix()
        for p in PACKAGE.rglob("*")
        if p.is_dir()
        and "__pycache__" not in p.parts
        and ((p / "__init__.py").is_file() or p.parent == PACKAGE)
    }
    return sorted(f for f in folders if f.rsplit("/", 1)[-1] not in named)


def test_every_path_the_architecture_names_exists() -> None:
    assert missing_paths(DOC.read_text(encoding="utf-8")) == []


def test_every_folder_of_the_package_is_described() -> None:
    assert unnamed_folders(DOC.read_text(encoding="utf-8")) == []


def test_a_path_that_is_gone_is_reported() -> None:
    text = "the verbs in `ros2/verbs/no_such_verb.py` and `lessons/no_such_folder/`"
    assert missing_paths(text) == ["lessons/no_such_folder/", "ros2/verbs/no_such_verb.py"]


def test_a_folder_left_out_is_reported() -> None:
    assert "dds" in unnamed_folders("only `core/` here")
