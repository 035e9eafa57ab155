"""The learners' and admins' Unix accounts: created by the hub's set-up (or found there), each
with a home closed to every other account; nothing else of an account is ever changed."""

from __future__ import annotations

import os
import pwd
import secrets
import stat
import subprocess
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path

import yaml

from ...core.errors import ConfigError, CourseError
from .settings import HUB_YAML, HubSettings

__all__ = [
    "FIRST_LEARNER_UID",
    "Account",
    "close_home",
    "ensure_accounts",
    "ensure_system_account",
    "refuse_system_accounts",
]

FIRST_LEARNER_UID = 1000  # below it: accounts of the system (root, daemon, www-data...)
PASSWORDS_FILE = "passwords.txt"


@dataclass(frozen=True)
class Account:
    """One person who may sign in, and whether set-up just created their Unix account."""

    name: str
    created: bool


def _item_line(path: Path, key: str, name: str) -> int | None:
    """Return the line of `name` in the YAML list `key` of `path` (for an error message)."""
    try:
        root = yaml.compose(path.read_text(encoding="utf-8"), Loader=yaml.SafeLoader)
    except (OSError, yaml.YAMLError):
        return None
    for key_node, value_node in getattr(root, "value", []):
        if key_node.value == key and isinstance(value_node, yaml.SequenceNode):
            for item in value_node.value:
                if item.value == name:
                    return item.start_mark.line + 1
    return None


def refuse_system_accounts(settings: HubSettings, source: Path = HUB_YAML) -> None:
    """Refuse a listed name that is an account of the system (root, daemon...): a learner's
    server would run with that account's rights."""
    for key in ("learners", "admins"):
        for name in getattr(settings, key):
            try:
                uid = pwd.getpwnam(name).pw_uid
            except KeyError:
                continue
            if uid < FIRST_LEARNER_UID:
                raise ConfigError(
                    str(source),
                    _item_line(source, key, name),
                    key,
                    f"{name!r} is an account of the system (uid {uid}), not a person's",
                    "choose another name for that learner or admin.",
                )


def _create(name: str, password: str | None) -> None:
    subprocess.run(
        ["useradd", "--create-home", "--user-group", "--shell", "/bin/bash", name],
        check=True,
        capture_output=True,
        text=True,
    )
    account = pwd.getpwnam(name)
    home = Path(account.pw_dir)
    owner = home.stat().st_uid
    if owner != account.pw_uid:
        # useradd keeps a folder that was there (a removed account's, with its files) and only
        # warns: the learner could not enter it and their server would never start
        subprocess.run(["userdel", name], check=False, capture_output=True)
        raise CourseError(
            f"Could not create the Unix account {name!r}: its home folder {home} is there "
            f"already, owned by uid {owner} (a removed account's?).",
            hint="move that folder away (or give it to an account yourself), then retry.",
        )
    home.chmod(0o700)  # a learner's notebooks and files are theirs alone
    if password is not None:
        subprocess.run(
            ["chpasswd"], input=f"{name}:{password}\n", check=True, capture_output=True, text=True
        )


def _record_passwords(state: Path, passwords: dict[str, str]) -> Path:
    """Append new initial passwords to the state folder's root-only list; return its path."""
    path = state / PASSWORDS_FILE
    lines = path.read_text(encoding="utf-8").splitlines() if path.exists() else []
    lines += [f"{name} {password}" for name, password in passwords.items()]
    partial = path.with_suffix(".partial")
    fd = os.open(partial, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    with os.fdopen(fd, "w", encoding="utf-8") as out:
        out.write("\n".join(lines) + "\n")
    partial.replace(path)
    return path


def close_home(name: str) -> str | None:
    """Close the home of account `name` to every other account, as the hub makes the homes of
    the accounts it creates; return a line saying what changed, or None.

    Only the permission bits of others go (the owner's stay); a home that is not a folder of
    that account's (missing, or a shared one such as /) is left alone. Raises CourseError,
    naming the account and the command, when root cannot close it (a root-squashed NFS home).
    """
    account = pwd.getpwnam(name)
    try:
        fd = os.open(account.pw_dir, os.O_RDONLY | os.O_DIRECTORY)
    except OSError:
        return None  # no home: their server says so as it starts
    try:  # checked and changed through one descriptor: the folder cannot be swapped between
        info = os.fstat(fd)
        mode = stat.S_IMODE(info.st_mode)
        if info.st_uid != account.pw_uid or mode & 0o077 == 0:
            return None
        os.fchmod(fd, mode & ~0o077)
    except OSError as err:
        raise CourseError(
            f"The home of {name!r}, {account.pw_dir}, is open to other accounts and the hub "
            f"cannot close it: {err.strerror}.",
            hint=f"as {name}, run `chmod go= {account.pw_dir}` (or list another account in "
            "config/hub.yaml), then retry.",
        ) from None
    finally:
        os.close(fd)
    return (
        f"Made the home of {name!r} private: {account.pw_dir} was open to other accounts "
        f"(mode {mode:o}), it is {mode & ~0o077:o} now."
    )


def ensure_accounts(
    names: Iterable[str],
    state: Path,
    *,
    with_password: bool,
    say: Callable[[str], None] = print,
) -> tuple[list[Account], Path | None]:
    """Create the missing Unix accounts (home folder private to its owner), and close the home
    of an existing one that other accounts could open (`say`ing so).

    With `with_password` (PAM sign-in) each new account gets a random initial password, written
    to `state/passwords.txt` (root only) for the instructor to hand out. Existing accounts keep
    their password. Returns the accounts and the password list's path if it was written.
    Needs root (the launcher checks it first).
    """
    accounts: list[Account] = []
    written: Path | None = None
    for name in names:
        try:
            pwd.getpwnam(name)
        except KeyError:
            pass
        else:  # made before the hub (Debian's homes are 0755): private, whoever made it
            closed = close_home(name)
            if closed is not None:
                say(closed)
            accounts.append(Account(name, created=False))
            continue
        password = secrets.token_urlsafe(9) if with_password else None
        try:
            _create(name, password)
        except subprocess.CalledProcessError as err:
            raise CourseError(
                f"Could not create the Unix account {name!r}: {err.stderr.strip()}",
                hint="create it yourself (`useradd --create-home NAME`), then retry.",
            ) from None
        if password is not None:  # recorded before the next account: none is ever lost
            written = _record_passwords(state, {name: password})
        accounts.append(Account(name, created=True))
    return accounts, written


def ensure_system_account(name: str) -> pwd.struct_passwd:
    """Return the system account `name` (a service's: no shell, no home, a group of its own),
    created if missing. Needs root."""
    try:
        return pwd.getpwnam(name)
    except KeyError:
        pass
    nologin = next((s for s in ("/usr/sbin/nologin", "/sbin/nologin") if Path(s).exists()), "")
    argv = ["useradd", "--system", "--user-group", "--no-create-home", "--home-dir", "/"]
    try:
        subprocess.run(
            [*argv, "--shell", nologin or "/bin/false", name],
            check=True, capture_output=True, text=True,
        )  # fmt: skip
    except subprocess.CalledProcessError as err:
        raise CourseError(
            f"Could not create the system account {name!r}: {err.stderr.strip()}",
            hint=f"create it yourself (`useradd --system --user-group {name}`), then retry.",
        ) from None
    return pwd.getpwnam(name)
