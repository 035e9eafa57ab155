"""The instructor's class settings (config/hub.yaml) as a frozen dataclass, read from a file
that keeps a demo's password to its owner."""

from __future__ import annotations

import contextlib
import ipaddress
import re
import stat
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import yaml

from ...config.loader import SettingValueError, display_path, load_settings, setting
from ...core.errors import ConfigError
from ...core.paths import config_dir

__all__ = ["HUB_YAML", "USER_NAME", "HubSettings", "load_hub_settings"]

HUB_YAML = config_dir() / "hub.yaml"
# Debian's useradd accepts these by default; 32 characters is Linux's limit for a user name.
USER_NAME = re.compile(r"[a-z_][a-z0-9_-]{0,31}")


def _check_names(key: str, names: tuple[str, ...]) -> None:
    seen: set[str] = set()
    for index, name in enumerate(names):
        where = f"{key}[{index}]"
        if not USER_NAME.fullmatch(name):
            raise SettingValueError(
                where,
                f"{name!r} is not a valid Unix user name",
                "use lower-case letters, digits, '-' and '_', starting with a letter "
                "(at most 32 characters), e.g. `alice` or `student-01`.",
            )
        if name in seen:
            raise SettingValueError(where, f"{name!r} is listed twice", "keep one of the two.")
        seen.add(name)


@dataclass(frozen=True)
class HubSettings:
    """What an instructor sets for a class: who signs in, where the hub listens, where it keeps
    its files."""

    learners: tuple[str, ...] = setting(help="one Unix user per learner", min_len=1)
    admins: tuple[str, ...] = setting(help="who sees the progress page", min_len=1)
    ip: str = setting("127.0.0.1", help="the address learners' browsers reach")
    port: int = setting(8000, help="the hub's public port", ge=1, le=65535)
    authenticator: Literal["pam", "shared-password"] = setting(
        "pam", help="pam: Unix passwords (a class); shared-password: one password (demo only)"
    )
    shared_password: str | None = setting(None, help="the demo's password", min_len=8)
    environment: str = setting(
        "/opt/ros2-params-course", help="where the environment every learner runs is built"
    )
    state: str = setting(
        "/var/lib/ros2-params-course", help="the hub's database, secrets and progress records"
    )
    python: str = setting("/usr/bin/python3.11", help="an interpreter every learner can run")
    idle_minutes: int = setting(60, help="stop a server idle this long (0: never)", ge=0)
    connections_per_account: int = setting(
        200, help="connections one account (or remote address) may hold to the hub", ge=16
    )

    def __post_init__(self) -> None:
        _check_names("learners", self.learners)
        _check_names("admins", self.admins)
        try:
            ipaddress.ip_address(self.ip)
        except ValueError:
            raise SettingValueError(
                "ip", f"{self.ip!r} is not an IP address", "use e.g. 127.0.0.1 or 0.0.0.0."
            ) from None
        if self.authenticator == "shared-password" and self.shared_password is None:
            raise SettingValueError(
                "authenticator",
                "shared-password needs `shared_password:`",
                "add `shared_password: <at least 8 characters>`, or use `pam` for a class.",
            )
        for key in ("environment", "state", "python"):
            if not Path(getattr(self, key)).is_absolute():
                raise SettingValueError(
                    key, f"{getattr(self, key)!r} is not an absolute path", "start it with /."
                )

    @property
    def users(self) -> tuple[str, ...]:
        """Return everyone who may sign in: the learners, then admins who are not learners."""
        return self.learners + tuple(a for a in self.admins if a not in self.learners)


def _key_line(path: Path, key: str) -> int | None:
    """Return the line of top-level `key` in the YAML file `path`, if it is there."""
    with contextlib.suppress(OSError, yaml.YAMLError):
        root = yaml.compose(path.read_text(encoding="utf-8"), Loader=yaml.SafeLoader)
        for key_node, _ in getattr(root, "value", []):
            if key_node.value == key:
                return int(key_node.start_mark.line) + 1
    return None


def _refuse_open_password(settings: HubSettings, path: Path) -> None:
    """Refuse a `shared_password` in a file other accounts may read: any of them could sign
    in as any learner with it."""
    mode = stat.S_IMODE(path.stat().st_mode)
    if settings.shared_password is None or mode & 0o077 == 0:
        return
    raise ConfigError(
        display_path(path),
        _key_line(path, "shared_password"),
        "shared_password",
        f"other accounts may read this file (mode {mode:o}), and any of them could sign in "
        "as any learner with it",
        f"keep it to its owner: `chmod 600 {path}`, then retry.",
    )


def load_hub_settings(path: str | Path | None = None) -> HubSettings:
    """Read config/hub.yaml (or `path`); raise ConfigError naming the file and line, or when
    the file holds a `shared_password` other accounts may read."""
    source = Path(path) if path is not None else HUB_YAML
    settings = load_settings(source, HubSettings)
    _refuse_open_password(settings, source)
    return settings
