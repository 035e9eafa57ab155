"""The proxy's route to a learner's server is a hard link root makes of the socket their
server listens on: a link the learner puts in their folder, or removes, routes nothing
elsewhere (before: the proxy followed it to another learner's server)."""

from __future__ import annotations

import contextlib
import os
import shutil
import socket
import stat
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest

from course_lib.hub.guard.routes import ROUTES_FOLDER, RouteError, forget_route, pin_route

pytestmark = pytest.mark.skipif(os.geteuid() != 0, reason="a listener of another uid: root")

LEARNER_UID, OTHER_UID = 61_001, 61_002  # no account needed: the kernel knows the uid


def _listen_as(uid: int, path: Path) -> int:
    """Fork a process of `uid` that listens on `path` and answers each connection with its
    own uid; return its pid."""
    ready_r, ready_w = os.pipe()
    pid = os.fork()
    if pid == 0:
        try:
            os.close(ready_r)
            os.setgid(uid)
            os.setuid(uid)
            server = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            server.bind(str(path))
            server.listen(8)
            os.write(ready_w, b"1")
            while True:
                conn, _ = server.accept()
                with contextlib.suppress(OSError):  # a probe that closed at once
                    conn.sendall(str(uid).encode())
                conn.close()
        finally:
            os._exit(0)
    os.close(ready_w)
    assert os.read(ready_r, 1) == b"1"
    os.close(ready_r)
    return pid


def _who_answers(path: Path) -> int:
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as client:
        client.connect(str(path))
        return int(client.recv(16))


@pytest.fixture
def sockets() -> Iterator[Path]:
    """A hub's sockets folder with a learner's and another learner's server listening (in
    the temp folder: pytest's own is closed to other uids)."""
    tmp_path = Path(tempfile.mkdtemp(prefix="hub-routes-"))
    tmp_path.chmod(0o711)
    pids = []
    for name, uid in (("ann", LEARNER_UID), ("bob", OTHER_UID)):
        (tmp_path / name).mkdir(mode=0o700)
        os.chown(tmp_path / name, uid, uid)
        pids.append(_listen_as(uid, tmp_path / name / "server.sock"))
    yield tmp_path
    for pid in pids:
        os.kill(pid, 9)
        os.waitpid(pid, 0)
    shutil.rmtree(tmp_path)


def test_the_route_reaches_the_learners_server_whatever_their_folder_holds_later(
    sockets: Path,
) -> None:
    route = pin_route(sockets / "ann" / "server.sock", sockets, "ann", LEARNER_UID)
    assert route.parent == sockets / ROUTES_FOLDER
    folder = route.parent.stat()
    assert stat.S_IMODE(folder.st_mode) == 0o700 and folder.st_uid == 0
    own = sockets / "ann" / "server.sock"
    own.unlink()
    own.symlink_to(sockets / "bob" / "server.sock")  # what the attack did, after the start
    assert [_who_answers(route) for _ in range(5)] == [LEARNER_UID] * 5
    assert _who_answers(own) == OTHER_UID  # the link itself goes elsewhere, unused
    forget_route(sockets, "ann")
    assert not route.exists()


def test_a_link_in_place_of_the_server_socket_is_never_routed(sockets: Path) -> None:
    own = sockets / "ann" / "server.sock"
    own.unlink()
    own.symlink_to(sockets / "bob" / "server.sock")
    with pytest.raises(RouteError, match="is a link"):
        pin_route(own, sockets, "ann", LEARNER_UID)
    assert list((sockets / ROUTES_FOLDER).iterdir()) == []


def test_another_accounts_socket_is_never_routed(sockets: Path) -> None:
    with pytest.raises(RouteError, match="not a socket of theirs"):
        pin_route(sockets / "bob" / "server.sock", sockets, "ann", LEARNER_UID)
    assert list((sockets / ROUTES_FOLDER).iterdir()) == []
