"""The hub's accounts: a password handed out is never lost, even when a later account fails;
every account's home is private, whoever made it."""

from __future__ import annotations

import os
import pwd
import secrets
import shutil
import subprocess
from pathlib import Path

import pytest
from unix_accounts import new_home

from course_lib.core.errors import CourseError
from course_lib.hub.provision.accounts import PASSWORDS_FILE, Account, ensure_accounts

pytestmark = pytest.mark.skipif(os.geteuid() != 0, reason="creates real Unix accounts")


def test_a_failing_account_keeps_the_passwords_of_those_created_before(tmp_path: Path) -> None:
    first, second = (f"crs{secrets.token_hex(4)}" for _ in range(2))
    # a group of the second's name makes the real `useradd --user-group` refuse it
    subprocess.run(["groupadd", second], check=True)
    try:
        with pytest.raises(CourseError, match=second):
            ensure_accounts([first, second], tmp_path, with_password=True)
        lines = (tmp_path / PASSWORDS_FILE).read_text().splitlines()
        assert [line.split()[0] for line in lines] == [first]
        assert (tmp_path / PASSWORDS_FILE).stat().st_mode & 0o777 == 0o600
    finally:
        subprocess.run(["userdel", "--remove", first], check=False, capture_output=True)
        subprocess.run(["groupdel", second], check=False, capture_output=True)


def test_a_home_folder_left_by_a_removed_account_is_refused_and_kept(tmp_path: Path) -> None:
    """useradd keeps a folder that is there and only warns; the learner could not enter it,
    and their server never started (the hub waited 120 s, then said it did not respond)."""
    name = f"crs{secrets.token_hex(4)}"
    home = new_home(name)
    home.mkdir(mode=0o700)
    (home / "notes.txt").write_text("theirs\n")
    os.chown(home, 3_999_999, 3_999_999)  # no account has it: a removed account's uid
    try:
        with pytest.raises(CourseError, match=f"{home} is there already, owned by uid 3999999"):
            ensure_accounts([name], tmp_path, with_password=True)
        with pytest.raises(KeyError):
            pwd.getpwnam(name)  # no account left half made
        assert (home / "notes.txt").read_text() == "theirs\n"
        assert not (tmp_path / PASSWORDS_FILE).exists()
    finally:
        subprocess.run(["userdel", name], check=False, capture_output=True)
        shutil.rmtree(home)


def test_an_account_made_before_the_hub_gets_a_private_home(tmp_path: Path) -> None:
    """Only the accounts the hub created had a 0700 home: another account read a learner's
    my_files/ in a home Debian's useradd had made 0755, and the hub said nothing."""
    name = f"crs{secrets.token_hex(4)}"
    subprocess.run(["useradd", "--create-home", name], check=True, capture_output=True)
    home = Path(pwd.getpwnam(name).pw_dir)
    home.chmod(0o755)
    said: list[str] = []
    try:
        accounts, written = ensure_accounts([name], tmp_path, with_password=True, say=said.append)
        assert accounts == [Account(name, created=False)] and written is None
        assert home.stat().st_mode & 0o7777 == 0o700
        assert said == [
            f"Made the home of {name!r} private: {home} was open to other accounts "
            "(mode 755), it is 700 now."
        ]
        ensure_accounts([name], tmp_path, with_password=True, say=said.append)
        assert len(said) == 1  # private already: nothing to say
    finally:
        subprocess.run(["userdel", "--remove", name], check=False, capture_output=True)


def test_a_home_that_is_not_the_accounts_own_is_never_changed(tmp_path: Path) -> None:
    """An account whose home is a folder of root's (/, a shared one) keeps it as it is."""
    name = f"crs{secrets.token_hex(4)}"
    shared = tmp_path / "shared"
    shared.mkdir()
    shared.chmod(0o755)
    argv = ["useradd", "--no-create-home", "--home-dir", str(shared), name]
    subprocess.run(argv, check=True, capture_output=True)
    said: list[str] = []
    try:
        ensure_accounts([name], tmp_path, with_password=True, say=said.append)
        assert shared.stat().st_mode & 0o777 == 0o755 and said == []
    finally:
        subprocess.run(["userdel", name], check=False, capture_output=True)
