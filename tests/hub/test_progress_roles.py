"""The progress service's hub settings agree with the installed JupyterHub's RBAC."""

from __future__ import annotations

from pathlib import Path

from course_lib.hub.progress import (
    ACCESS_SCOPE,
    SERVICE_NAME,
    roles,
    service_command,
    service_spec,
)


def test_the_server_role_keeps_jupyterhubs_scopes_and_adds_the_access_scope() -> None:
    from jupyterhub.roles import get_default_roles

    default = {r["name"]: set(r["scopes"]) for r in get_default_roles()}
    ours = {r["name"]: set(r["scopes"]) for r in roles()}
    assert default["server"] < ours["server"], "a server token must still post activity"
    assert default["user"] < ours["user"], "users keep `self`"
    # a server token holds only what its owner holds: the user role must grant what it adds
    assert ours["server"] - default["server"] <= ours["user"] == {"self", ACCESS_SCOPE}


def test_the_service_may_list_users_and_nothing_more() -> None:
    (service_role,) = [r for r in roles() if r.get("services")]
    assert service_role["services"] == [SERVICE_NAME]
    assert set(service_role["scopes"]) == {"list:users", "read:users:name"}
    # that JupyterHub knows every scope is proven by the hub tests: a hub refuses to start


def test_the_service_spec_is_an_external_service_on_its_port() -> None:
    spec = service_spec(8123, "t0ken")
    assert spec["name"] == SERVICE_NAME and spec["url"] == "http://127.0.0.1:8123"
    assert "command" not in spec, "the launcher starts it, on the socket it bound"
    assert spec["api_token"] == "t0ken" and spec["oauth_no_confirm"] is True
    assert service_command("python3", Path("state", "progress.sqlite")) == [
        "python3", "-m", "course_lib.hub.progress", "--db", str(Path("state", "progress.sqlite"))
    ]  # fmt: skip
