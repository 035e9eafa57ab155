"""Runtime folders a deleted account left: removed before another account with its uid has them.

The course keeps an account's locks, sockets and parameter journal in a folder named by uid
(course_lib/core/runtime_folder.py), which it takes as its own when that uid owns it: an
account made with a deleted one's uid inherited that one's journal, markers and sockets. The
hub (root) removes, at its start, the folders of uids that have no account any more, and,
before each learner's server starts, those of another account with the learner's uid: it
records in its root-only state folder which account (name, home folder) each uid's folders
were last kept for. Only a directory owned by that uid is removed, never through a link.
"""

from __future__ import annotations

import json
import os
import pwd
import stat
import tempfile
from collections.abc import Callable, Iterable
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from .tree_removal import remove_tree

__all__ = [
    "RECORD_NAME",
    "AccountIdentity",
    "Removal",
    "account_identity",
    "clear_for_account",
    "folder_uid",
    "remove_orphaned_folders",
    "runtime_folders",
    "temp_folders",
]

RECORD_NAME = "runtime-owners.json"  # in the hub's state folder: uid -> AccountIdentity
_PREFIX = "ros2-course-"  # + uid: a runtime folder in a temp folder


@dataclass(frozen=True)
class AccountIdentity:
    """What differs when an account is deleted and another is made with its uid."""

    name: str
    home: str
    home_inode: tuple[int, int] | None  # (device, inode) of the home; None: no home


@dataclass(frozen=True)
class Removal:
    """One runtime folder removed, and whose it was."""

    path: Path
    uid: int
    learner: str | None = None  # whose server was about to start; None: at the hub's start
    left_by: str | None = None  # the account recorded for that uid; None: none recorded

    def line(self) -> str:
        """Return the hub log's line for it."""
        if self.learner is None:
            return (
                f"Removed {self.path}: the course's runtime folder of uid {self.uid}, which has "
                "no account any more (the next account with that uid would inherit it)."
            )
        whose = (
            f"the account {self.left_by!r} left (another account, before theirs)"
            if self.left_by
            else "made before the hub first started their server (maybe by another account)"
        )
        return (
            f"Removed {self.path} before {self.learner}'s server started: a runtime folder of "
            f"uid {self.uid} {whose}, not theirs to inherit."
        )


def temp_folders() -> list[Path]:
    """Return the temp folders where runtime folders are made (Python's and /tmp)."""
    return [Path(p) for p in dict.fromkeys((tempfile.gettempdir(), "/tmp"))]


def folder_uid(name: str) -> int | None:
    """Return the uid a folder named `name` is the runtime folder of (`ros2-course-1001`)."""
    digits = name.removeprefix(_PREFIX)
    if digits == name or not (digits.isascii() and digits.isdigit()):
        return None
    return int(digits) if str(int(digits)) == digits else None


def runtime_folders(uid: int) -> list[Path]:
    """Return where the runtime folders of `uid` may be, outside its home."""
    found = [temp / f"{_PREFIX}{uid}" for temp in temp_folders()]
    return [*found, Path(f"/run/user/{uid}/ros2-course")]  # its XDG_RUNTIME_DIR's


def _owned_folder(path: Path, uid: int) -> bool:
    """Say whether `path` itself (not what a link names) is a directory of `uid`."""
    try:
        info = os.lstat(path)
    except OSError:
        return False
    return stat.S_ISDIR(info.st_mode) and info.st_uid == uid


def _has_account(uid: int) -> bool:
    try:
        pwd.getpwuid(uid)
    except KeyError:
        return False
    return True


def _running_uids() -> set[int]:
    """Return the uids of every running process."""
    uids = set()
    for entry in Path("/proc").iterdir():
        try:
            if entry.name.isdigit():
                uids.add(entry.stat().st_uid)
        except OSError:
            continue
    return uids


def remove_orphaned_folders(
    temps: Iterable[Path] | None = None,
    *,
    has_account: Callable[[int], bool] = _has_account,
    running: Callable[[], set[int]] = _running_uids,
) -> list[Removal]:
    """Remove the runtime folders of uids with no account and no process; return them."""
    active = running()
    removed = []
    for temp in temp_folders() if temps is None else temps:
        for path in sorted(Path(temp).glob(f"{_PREFIX}*")):
            uid = folder_uid(path.name)
            if uid is None or uid in active or has_account(uid) or not _owned_folder(path, uid):
                continue
            if remove_tree(path):
                removed.append(Removal(path, uid))
    return removed


def account_identity(name: str) -> tuple[int, AccountIdentity]:
    """Return `name`'s uid and identity (KeyError: no such account)."""
    account = pwd.getpwnam(name)
    try:
        info = os.stat(account.pw_dir)
        inode: tuple[int, int] | None = (info.st_dev, info.st_ino)
    except OSError:
        inode = None
    return account.pw_uid, AccountIdentity(name, account.pw_dir, inode)


def _from_json(item: dict[str, Any]) -> AccountIdentity:
    inode = item["home_inode"]
    home_inode = (int(inode[0]), int(inode[1])) if inode else None
    return AccountIdentity(str(item["name"]), str(item["home"]), home_inode)


def _read_record(path: Path) -> dict[int, AccountIdentity]:
    """Return the record; an unreadable one is empty (every folder then goes once)."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        return {int(uid): _from_json(item) for uid, item in data.items()}
    except (OSError, ValueError, TypeError, KeyError, IndexError, AttributeError):
        return {}


def _write_record(path: Path, record: dict[int, AccountIdentity]) -> None:
    partial = path.with_name(path.name + ".partial")
    fd = os.open(partial, os.O_WRONLY | os.O_CREAT | os.O_TRUNC | os.O_NOFOLLOW, 0o600)
    with os.fdopen(fd, "w", encoding="utf-8") as out:
        json.dump({str(uid): asdict(item) for uid, item in sorted(record.items())}, out)
    partial.replace(path)


def clear_for_account(
    uid: int, identity: AccountIdentity, state: Path, folders: Iterable[Path] | None = None
) -> list[Removal]:
    """Before `identity`'s server starts: remove the runtime folders of `uid` unless the
    record says they were kept for this very account, then record it; return what went.

    With no record for `uid` (the hub never started this account's server) nothing says the
    folders are this account's: they go (they live in temp folders, lost at a reboot anyway).
    `folders` are where to look (runtime_folders(uid) unless given).
    """
    record_path = state / RECORD_NAME
    record = _read_record(record_path)
    earlier = record.get(uid)
    removed = []
    if earlier != identity:
        for path in runtime_folders(uid) if folders is None else folders:
            if _owned_folder(path, uid) and remove_tree(path):
                left_by = earlier.name if earlier else None
                removed.append(Removal(path, uid, identity.name, left_by))
        record[uid] = identity
        _write_record(record_path, record)
    return removed
