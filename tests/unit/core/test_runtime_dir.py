"""The runtime folder (locks, markers, sockets) is private, verified, and short enough."""

from __future__ import annotations

import os
import shutil
import socket
import stat
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest

from course_lib.core.errors import RuntimeDirError
from course_lib.core.paths import SOCKET_NAME_MAX, runtime_dir


@pytest.fixture
def tmpdir_is(monkeypatch: pytest.MonkeyPatch):  # type: ignore[no-untyped-def]
    """Point TMPDIR (as tempfile sees it) at a folder; no XDG_RUNTIME_DIR."""
    monkeypatch.delenv("XDG_RUNTIME_DIR", raising=False)

    def use(folder: Path) -> Path:
        folder.mkdir(parents=True, exist_ok=True)
        monkeypatch.setenv("TMPDIR", str(folder))
        monkeypatch.setattr(tempfile, "tempdir", None)  # gettempdir() reads TMPDIR again
        return folder / f"ros2-course-{os.getuid()}"

    return use


@pytest.fixture
def short_tmp() -> Iterator[Path]:
    """Yield a new folder with a short path (pytest's own can be too long for sockets)."""
    folder = Path(tempfile.mkdtemp(prefix="rt"))
    yield folder
    shutil.rmtree(folder, ignore_errors=True)


def test_created_private_under_tmpdir(tmpdir_is, short_tmp: Path) -> None:
    expected = tmpdir_is(short_tmp)
    assert runtime_dir() == expected
    assert len(os.fsencode(expected)) + 1 + SOCKET_NAME_MAX < 108
    info = expected.lstat()
    assert stat.S_IMODE(info.st_mode) == 0o700 and info.st_uid == os.getuid()
    assert runtime_dir() == expected  # a second call accepts the folder it made


def test_open_to_others_is_refused_with_the_fix(tmpdir_is, short_tmp: Path) -> None:
    folder = tmpdir_is(short_tmp)
    folder.mkdir(mode=0o700)
    folder.chmod(0o755)
    with pytest.raises(RuntimeDirError) as raised:
        runtime_dir()
    assert "open to other users (mode 755)" in str(raised.value)
    assert f"chmod 700 {folder}" in str(raised.value)


@pytest.fixture
def home_is(monkeypatch: pytest.MonkeyPatch, short_tmp: Path):  # type: ignore[no-untyped-def]
    """Make the temp folders (TMPDIR's and /tmp) one folder and HOME another; return the
    home's runtime folder."""
    import course_lib.core.runtime_folder as runtime_folder

    monkeypatch.setattr(runtime_folder, "_POSIX_TMP", str(short_tmp))
    home = short_tmp / "home"
    home.mkdir()
    monkeypatch.setenv("HOME", str(home))
    return home / ".cache" / "ros2-course" / "run"


def test_a_link_squatting_the_name_is_passed_over(tmpdir_is, home_is, short_tmp: Path) -> None:
    """Anyone can make a link in /tmp: the course goes to a folder nobody else can make."""
    target = short_tmp / "elsewhere"
    target.mkdir(mode=0o700)
    tmpdir_is(short_tmp).symlink_to(target)
    assert runtime_dir() == home_is
    assert stat.S_IMODE(home_is.lstat().st_mode) == 0o700


@pytest.mark.skipif(os.geteuid() != 0, reason="giving a folder to another user needs root")
def test_a_folder_squatted_by_another_user_is_passed_over(
    tmpdir_is, home_is, short_tmp: Path
) -> None:
    folder = tmpdir_is(short_tmp)
    folder.mkdir(mode=0o700)
    os.chown(folder, 65534, 65534)  # nobody made it first
    assert runtime_dir() == home_is
    # with no safe folder left at all, the refusal says whose it is and what to do
    shutil.rmtree(home_is)
    home_is.parent.mkdir(parents=True, exist_ok=True)
    home_is.mkdir(mode=0o700)
    os.chown(home_is, 65534, 65534)
    with pytest.raises(RuntimeDirError) as raised:
        runtime_dir()
    assert "belongs to another user (uid 65534)" in str(raised.value)
    assert "TMPDIR" in str(raised.value)


def test_sockets_fit_whatever_tmpdir_is(tmpdir_is, tmp_path: Path) -> None:
    long_tmp = tmp_path.joinpath(*["a_very_long_folder_name_" * 2] * 4)
    assert len(str(long_tmp)) > 108
    tmpdir_is(long_tmp)
    folder = runtime_dir()
    info = folder.lstat()
    assert stat.S_IMODE(info.st_mode) == 0o700 and info.st_uid == os.getuid()
    path = folder / f"test-{os.getpid()}".ljust(SOCKET_NAME_MAX, "x")
    assert len(os.fsencode(path)) < 108
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as server:
        server.bind(str(path))  # would raise "AF_UNIX path too long" past the limit
        path.unlink()
