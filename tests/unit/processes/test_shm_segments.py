"""Leftover Fast DDS segments: removed when nobody holds their lock, kept otherwise."""

from __future__ import annotations

import fcntl
import os
import sys
import time
from pathlib import Path

import pytest

from course_lib.processes.shm_segments import Swept, sweep_stale_segments
from course_lib.processes.stopping import StopReport

HOUR = 3600.0


def _segment(folder: Path, name: str, *, age_s: float = HOUR, size: int = 1000) -> Path:
    (folder / name).write_bytes(b"\0" * size)
    lock = folder / f"{name}_el"
    lock.touch()
    then = time.time() - age_s
    os.utime(lock, (then, then))
    return lock


def test_a_segment_nobody_holds_is_removed_with_its_lock_file(tmp_path: Path) -> None:
    _segment(tmp_path, "fastrtps_0123456789abcdef", size=549408)
    swept = sweep_stale_segments(tmp_path)
    assert swept == Swept(1, 549408)
    assert list(tmp_path.iterdir()) == []
    assert swept.sentence() == (
        "Removed 1 shared-memory segment(s) (0.5 MiB) that killed ROS processes had left in "
        "/dev/shm."
    )


def test_a_live_participants_segment_is_kept(tmp_path: Path) -> None:
    lock = _segment(tmp_path, "fastrtps_00000000000000aa")
    fd = os.open(lock, os.O_RDWR)  # the participant's hold (another open file: flock conflicts)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        assert sweep_stale_segments(tmp_path) == Swept()
    finally:
        os.close(fd)
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "fastrtps_00000000000000aa",
        "fastrtps_00000000000000aa_el",
    ]


def _port(folder: Path, name: str, first_word: int, *, age_s: float = HOUR) -> Path:
    port = folder / name
    port.write_bytes(first_word.to_bytes(4, sys.byteorder) + b"\0" * 52396)
    then = time.time() - age_s
    os.utime(port, (then, then))
    return port


def test_a_young_segment_and_the_shared_port_segments_are_kept(tmp_path: Path) -> None:
    _segment(tmp_path, "fastrtps_00000000000000bb", age_s=5.0)  # its participant may lock it now
    _segment(tmp_path, "fastrtps_port7000")  # shared by the port's next participants
    _port(tmp_path, "fastrtps_port7000", 2)  # made whole (boost.interprocess's mark)
    _port(tmp_path, "fastrtps_port7001", 0, age_s=5.0)  # its maker may be making it now
    (tmp_path / "sem.fastrtps_port7000_mutex").touch()
    _segment(tmp_path, "not_fastdds_0123456789abcdef")
    before = sorted(p.name for p in tmp_path.iterdir())
    assert sweep_stale_segments(tmp_path) == Swept()
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_a_port_segment_its_maker_never_finished_is_removed(tmp_path: Path) -> None:
    # Fast DDS waits forever for such a port to be made: every participant that reached
    # port 7005 on the host hung in rclpy.init (a lesson's start() with the host idle).
    _port(tmp_path, "fastrtps_port7005", 0)  # never begun
    _port(tmp_path, "fastrtps_port7006", 1)  # begun, its maker gone
    (tmp_path / "fastrtps_port7007").touch(mode=0o644)
    then = time.time() - HOUR
    os.utime(tmp_path / "fastrtps_port7007", (then, then))  # not even sized
    _port(tmp_path, "fastrtps_port7008", 2)
    assert sweep_stale_segments(tmp_path) == Swept(3, 2 * 52400)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fastrtps_port7008"]


def test_a_lock_file_alone_is_removed_and_not_counted(tmp_path: Path) -> None:
    _segment(tmp_path, "fastrtps_00000000000000cc")
    (tmp_path / "fastrtps_00000000000000cc").unlink()
    assert sweep_stale_segments(tmp_path) == Swept()
    assert list(tmp_path.iterdir()) == []


@pytest.mark.skipif(os.geteuid() != 0, reason="making another user's file needs root")
def test_another_users_segment_is_kept(tmp_path: Path) -> None:
    lock = _segment(tmp_path, "fastrtps_00000000000000dd")
    os.chown(lock, 12345, 12345)
    assert sweep_stale_segments(tmp_path) == Swept()
    assert (tmp_path / "fastrtps_00000000000000dd").exists()


def test_no_shm_folder_sweeps_nothing(tmp_path: Path) -> None:
    assert sweep_stale_segments(tmp_path / "missing") == Swept()


def test_make_stop_says_what_it_swept() -> None:
    said = StopReport(swept=Swept(3, 3 * 549408)).render().splitlines()
    assert said == [
        "No course process runs.",
        "Removed 3 shared-memory segment(s) (1.6 MiB) that killed ROS processes had left in "
        "/dev/shm.",
    ]
