"""The hub's accounts: a password handed out is never lost, even when a later account fails."""

from __future__ import annotations

import os
import secrets
import subprocess
from pathlib import Path

import pytest

from course_lib.core.errors import CourseError
from course_lib.hub.accounts import PASSWORDS_FILE, ensure_accounts

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
