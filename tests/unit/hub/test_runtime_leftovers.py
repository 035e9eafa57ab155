"""Runtime folders a deleted account left: those of uids with no account go at the hub's start,
another account's go before a learner's server starts, and nothing but a directory of that uid
is ever removed (the hub's real start: tests/hub/test_hub_runtime_leftovers.py)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from course_lib.hub.guard.runtime_leftovers import (
    RECORD_NAME,
    AccountIdentity,
    Removal,
    clear_for_account,
    folder_uid,
    remove_orphaned_folders,
)

ME = os.getuid()
LEARNER = AccountIdentity("r2pu-new", "/home/r2pu-new", (64, 1201))
EARLIER = AccountIdentity("r2pu-old", "/home/r2pu-old", (64, 1187))


def _runtime_folder(temp: Path, uid: int = ME) -> Path:
    """Make a runtime folder of `uid`'s name in `temp` (owned by this test), a journal in it."""
    folder = temp / f"ros2-course-{uid}"
    folder.mkdir(0o700)
    (folder / "param-journal-0.jsonl").write_text('{"t": "set"}\n', encoding="utf-8")
    return folder


@pytest.mark.parametrize(
    ("name", "uid"),
    [
        ("ros2-course-1001", 1001),
        ("ros2-course-0", 0),
        ("ros2-course-01001", None),  # not a name runtime_folder() makes
        ("ros2-course-", None),
        ("ros2-course-hub-env-0061c9e042", None),
        ("ros2-course-\u0661\u0662", None),  # digits, but not ASCII ones
        ("ros2-course--5", None),
        ("other-1001", None),
    ],
)
def test_folder_uid_reads_only_the_names_runtime_folders_have(name: str, uid: int | None) -> None:
    assert folder_uid(name) == uid


def test_a_folder_of_a_uid_with_no_account_and_no_process_goes(tmp_path: Path) -> None:
    folder = _runtime_folder(tmp_path)
    removed = remove_orphaned_folders([tmp_path], has_account=lambda uid: False, running=set)
    assert removed == [Removal(folder, ME)]
    assert not os.path.lexists(folder)
    assert removed[0].line().startswith(f"Removed {folder}: the course's runtime folder of uid")


def test_a_folder_with_an_account_or_a_running_process_stays(tmp_path: Path) -> None:
    folder = _runtime_folder(tmp_path)
    assert remove_orphaned_folders([tmp_path], has_account=lambda uid: True, running=set) == []
    kept = remove_orphaned_folders([tmp_path], has_account=lambda uid: False, running=lambda: {ME})
    assert kept == [] and folder.is_dir()


def test_only_a_directory_that_uid_owns_is_removed(tmp_path: Path) -> None:
    """A link is never followed, a file is not a runtime folder, and a folder named for
    another uid than its owner's is not one that uid left."""
    (tmp_path / "elsewhere").mkdir()
    elsewhere = _runtime_folder(tmp_path / "elsewhere")
    link = tmp_path / f"ros2-course-{ME}"
    link.symlink_to(elsewhere)
    (tmp_path / f"ros2-course-{ME + 1}").mkdir()  # this test's, not uid ME + 1's
    (tmp_path / f"ros2-course-{ME + 2}").write_text("", encoding="utf-8")
    assert remove_orphaned_folders([tmp_path], has_account=lambda uid: False, running=set) == []
    assert link.is_symlink() and (elsewhere / "param-journal-0.jsonl").is_file()
    assert (tmp_path / f"ros2-course-{ME + 1}").is_dir()


def test_a_learner_the_hub_never_started_gets_no_folder_of_their_uid(tmp_path: Path) -> None:
    """Nothing says whose it is: it goes, and the record now says it is theirs (0600)."""
    state, folder = tmp_path / "state", _runtime_folder(tmp_path)
    state.mkdir(0o700)
    removed = clear_for_account(ME, LEARNER, state, [folder])
    assert removed == [Removal(folder, ME, "r2pu-new", None)]
    assert not os.path.lexists(folder)
    assert "before r2pu-new's server started" in removed[0].line()
    assert (state / RECORD_NAME).stat().st_mode & 0o777 == 0o600


def test_the_same_account_keeps_its_folder_from_one_server_to_the_next(tmp_path: Path) -> None:
    state = tmp_path / "state"
    state.mkdir(0o700)
    clear_for_account(ME, LEARNER, state, [tmp_path / f"ros2-course-{ME}"])
    folder = _runtime_folder(tmp_path)  # their lab made it
    assert clear_for_account(ME, LEARNER, state, [folder]) == []
    assert (folder / "param-journal-0.jsonl").is_file()


def test_another_account_with_that_uid_loses_the_earlier_ones_folder(tmp_path: Path) -> None:
    state = tmp_path / "state"
    state.mkdir(0o700)
    clear_for_account(ME, EARLIER, state, [tmp_path / f"ros2-course-{ME}"])
    folder = _runtime_folder(tmp_path)  # the earlier account's lab made it, then it went
    removed = clear_for_account(ME, LEARNER, state, [folder])
    assert removed == [Removal(folder, ME, "r2pu-new", "r2pu-old")]
    assert "'r2pu-old' left" in removed[0].line()
    assert not os.path.lexists(folder)
    # made again with the same name: another home, so another account
    again = _runtime_folder(tmp_path)
    remade = AccountIdentity("r2pu-new", "/home/r2pu-new", (64, 1300))
    assert clear_for_account(ME, remade, state, [again]) != []


def test_an_unreadable_record_keeps_no_folder(tmp_path: Path) -> None:
    state = tmp_path / "state"
    state.mkdir(0o700)
    (state / RECORD_NAME).write_text("{not json", encoding="utf-8")
    folder = _runtime_folder(tmp_path)
    assert clear_for_account(ME, LEARNER, state, [folder]) != []
    assert not os.path.lexists(folder)


def test_a_link_in_the_folders_place_is_never_followed(tmp_path: Path) -> None:
    state, elsewhere = tmp_path / "state", tmp_path / "elsewhere"
    state.mkdir(0o700)
    elsewhere.mkdir()
    target = _runtime_folder(elsewhere)
    link = tmp_path / f"ros2-course-{ME}"
    link.symlink_to(target)
    assert clear_for_account(ME, LEARNER, state, [link]) == []
    assert link.is_symlink() and (target / "param-journal-0.jsonl").is_file()
