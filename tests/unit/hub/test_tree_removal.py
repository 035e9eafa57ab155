"""remove_tree: a folder tree of any depth goes without recursion, links are never followed,
and a level moved out of the tree ends the walk there."""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest

from course_lib.core.paths import REPO_ROOT
from course_lib.hub.guard.tree_removal import _climb, _identity, remove_tree

NOBODY = 65534


def _nest(top: Path, depth: int) -> None:
    """Make `depth` folders one inside the other under `top`, a file in every tenth (relative
    to each level: the whole path is far past PATH_MAX)."""
    top.mkdir()
    fd = os.open(top, os.O_RDONLY | os.O_DIRECTORY)
    try:
        for level in range(depth):
            os.mkdir("d", dir_fd=fd)
            inner = os.open("d", os.O_RDONLY | os.O_DIRECTORY, dir_fd=fd)
            os.close(fd)
            fd = inner
            if level % 10 == 0:
                os.close(os.open("f", os.O_WRONLY | os.O_CREAT, 0o644, dir_fd=fd))
    finally:
        os.close(fd)


def test_a_tree_deeper_than_the_call_stack_is_removed(tmp_path: Path) -> None:
    """A learner nested 1,200 folders in their socket folder: shutil.rmtree raised
    RecursionError on Python 3.11 and the hub's stop ended in a traceback."""
    tree = tmp_path / "sockets"
    _nest(tree, 1200)
    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(200)  # the walk keeps a list: no level takes a frame
    try:
        assert remove_tree(tree) is True
    finally:
        sys.setrecursionlimit(limit)
    assert not tree.exists() and list(tmp_path.iterdir()) == []


def test_a_deep_tree_needs_only_a_few_open_files(tmp_path: Path) -> None:
    """One descriptor per level (Python 3.13's iterative rmtree) would run out at 1,024."""
    tree = tmp_path / "sockets"
    _nest(tree, 1200)
    code = (
        "import resource, sys\n"
        "_, hard = resource.getrlimit(resource.RLIMIT_NOFILE)\n"
        "resource.setrlimit(resource.RLIMIT_NOFILE, (24, hard))\n"
        "from course_lib.hub.guard.tree_removal import remove_tree\n"
        "print(remove_tree(sys.argv[1]))\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", code, str(tree)],
        cwd=REPO_ROOT, capture_output=True, text=True, timeout=120, check=False,
    )  # fmt: skip
    assert done.stdout.strip() == "True", done.stderr
    assert not tree.exists()


def test_links_in_the_tree_are_removed_never_followed(tmp_path: Path) -> None:
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "keep.txt").write_text("not the learner's\n")
    tree = tmp_path / "tree" / "inner"
    tree.mkdir(parents=True)
    (tree / "to-folder").symlink_to(outside, target_is_directory=True)
    (tree / "to-file").symlink_to(outside / "keep.txt")
    assert remove_tree(tmp_path / "tree") is True
    assert (outside / "keep.txt").read_text() == "not the learner's\n"


def test_a_file_a_link_or_nothing_at_the_path(tmp_path: Path) -> None:
    (tmp_path / "file").write_text("x")
    (tmp_path / "link").symlink_to(tmp_path / "elsewhere")
    (tmp_path / "elsewhere").mkdir()
    assert remove_tree(tmp_path / "file") is True
    assert remove_tree(tmp_path / "link") is True
    assert (tmp_path / "elsewhere").is_dir()
    assert remove_tree(tmp_path / "never-made") is True


def test_climbing_into_a_folder_other_than_the_one_left_is_refused(tmp_path: Path) -> None:
    """A learner who moves the level being emptied out of the tree (to /run/lock, say) must
    not lead the walk into that folder: `..` is checked against the folder it came from."""
    (tmp_path / "tree" / "level").mkdir(parents=True)
    (tmp_path / "elsewhere").mkdir()
    tree = os.open(tmp_path / "tree", os.O_RDONLY | os.O_DIRECTORY)
    level = os.open(tmp_path / "tree" / "level", os.O_RDONLY | os.O_DIRECTORY)
    try:
        came_from = _identity(tree)
        parent = _climb(level, came_from)
        assert parent is not None
        os.close(parent)
        (tmp_path / "tree" / "level").rename(tmp_path / "elsewhere" / "level")
        assert _climb(level, came_from) is None
    finally:
        os.close(level)
        os.close(tree)


@pytest.fixture
def open_folder() -> Iterator[Path]:
    """A folder every account reaches (pytest's own is root's alone)."""
    folder = Path(tempfile.mkdtemp(prefix="tree-removal-"))
    folder.chmod(0o755)
    try:
        yield folder
    finally:
        subprocess.run(["chmod", "-R", "u+rwx", str(folder)], check=False)
        subprocess.run(["rm", "-rf", str(folder)], check=False)


def test_what_cannot_be_removed_stays_and_the_walk_ends(open_folder: Path) -> None:
    """A folder the remover may not open is left (said by the result), not retried forever."""
    tree = open_folder / "tree"
    (tree / "closed").mkdir(parents=True)
    (tree / "closed" / "inside.txt").write_text("x")
    (tree / "open" / "deep").mkdir(parents=True)
    (tree / "loose.txt").write_text("x")
    (tree / "closed").chmod(0o000)
    if os.geteuid() == 0:  # root opens any folder: remove as an account that cannot
        subprocess.run(["chown", "-R", f"{NOBODY}:{NOBODY}", str(tree)], check=True)

    def become() -> None:
        if os.geteuid() == 0:
            os.setgroups([])
            os.setgid(NOBODY)
            os.setuid(NOBODY)

    code = "import sys; from course_lib.hub.guard.tree_removal import remove_tree\n"
    code += "print(remove_tree(sys.argv[1]))\n"
    # the course's interpreter may be under root's private home: Debian's is everyone's
    python = "/usr/bin/python3" if os.geteuid() == 0 else sys.executable
    done = subprocess.run(
        [python, "-c", code, str(tree)], cwd=REPO_ROOT, preexec_fn=become,
        capture_output=True, text=True, timeout=60, check=False,
    )  # fmt: skip
    assert done.stdout.strip() == "False", done.stderr
    assert sorted(p.name for p in tree.iterdir()) == ["closed"]
