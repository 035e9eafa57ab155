"""config/hub.yaml: the class's settings, and the line named for each mistake."""

from __future__ import annotations

from pathlib import Path

import pytest

from course_lib.core.errors import ConfigError
from course_lib.hub.provision.settings import HUB_YAML, load_hub_settings

GOOD = """\
learners:
  - alice
  - bob
admins: [teacher]
"""


def _load(tmp_path: Path, text: str):  # type: ignore[no-untyped-def]
    path = tmp_path / "hub.yaml"
    path.write_text(text, encoding="utf-8")
    return load_hub_settings(path)


def test_the_shipped_file_loads() -> None:
    settings = load_hub_settings(HUB_YAML)
    assert settings.authenticator == "pam" and settings.ip == "127.0.0.1"
    assert settings.learners and settings.admins


def test_defaults_and_users(tmp_path: Path) -> None:
    settings = _load(tmp_path, GOOD)
    assert settings.users == ("alice", "bob", "teacher")
    assert settings.port == 8000 and settings.python == "/usr/bin/python3.11"


def test_an_admin_who_is_also_a_learner_signs_in_once(tmp_path: Path) -> None:
    settings = _load(tmp_path, "learners: [alice, teacher]\nadmins: [teacher]\n")
    assert settings.users == ("alice", "teacher")


@pytest.mark.parametrize(
    ("text", "line", "words"),
    [
        ("learners:\n  - alice\n  - bob\n  - alice\nadmins: [t]\n", 4, "listed twice"),
        ("learners:\n  - alice\n  - Bob Smith\nadmins: [t]\n", 3, "not a valid Unix user name"),
        ("learners: [alice]\nadmins:\n  - 9lives\n", 3, "not a valid Unix user name"),
        ("learners: []\nadmins: [t]\n", 1, "out of range"),
        (GOOD + "ip: localhost\n", 5, "not an IP address"),
        (GOOD + "port: 70000\n", 5, "out of range"),
        (GOOD + "authenticator: shared-password\n", 5, "needs `shared_password:`"),
        (GOOD + "authenticator: github\n", 5, "is not one of"),
        (GOOD + "environment: opt/course\n", 5, "not an absolute path"),
        (GOOD + "learner: [x]\n", 5, "unknown key"),
    ],
)
def test_mistakes_name_file_and_line(tmp_path: Path, text: str, line: int, words: str) -> None:
    with pytest.raises(ConfigError) as caught:
        _load(tmp_path, text)
    message = str(caught.value)
    assert f"hub.yaml, line {line}" in message or f"hub.yaml:{line}" in message, message
    assert words in message, message


def test_a_shared_password_other_accounts_may_read_is_refused(tmp_path: Path) -> None:
    """Any account that reads the demo's password signs in as any learner with it."""
    text = GOOD + "authenticator: shared-password\nshared_password: demo-password\n"
    path = tmp_path / "hub.yaml"
    path.write_text(text, encoding="utf-8")
    path.chmod(0o644)  # what git and an editor leave by default
    with pytest.raises(ConfigError) as caught:
        load_hub_settings(path)
    message = str(caught.value)
    assert "hub.yaml, line 6: shared_password" in message, message
    assert "(mode 644)" in message and f"chmod 600 {path}" in message, message
    path.chmod(0o600)
    assert load_hub_settings(path).shared_password == "demo-password"
