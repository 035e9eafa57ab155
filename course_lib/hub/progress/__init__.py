"""The course-progress service: the instructor's page of every learner's self-checks.

It is an external JupyterHub service (`python -m course_lib.hub.progress`), served at
`/services/course-progress/`: the class hub's launcher starts it on a socket it bound itself,
as an account of its own (course_lib/hub/progress_service.py); on Kubernetes it is a pod.
Lessons' self-checks post their verdict to it with the learner's own hub token (see
course_lib/lessons/progress/client.py); admins read the page.

This module is what the hub's config calls. It imports neither JupyterHub nor tornado, so a
learner's kernel may import it for the names below.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

# the wire format's names: the lessons' side of the contract owns them
from ...lessons.progress.record import LESSONS, PROGRESS_HOLDER_ENV, PROGRESS_URL_ENV

__all__ = [
    "ACCESS_SCOPE",
    "DB_ENV",
    "LESSONS",
    "PROGRESS_HOLDER_ENV",
    "PROGRESS_URL_ENV",
    "SERVICE_NAME",
    "roles",
    "service_command",
    "service_environment",
    "service_spec",
]

SERVICE_NAME = "course-progress"
DB_ENV = "COURSE_PROGRESS_DB"  # the SQLite file, when --db is not given
ACCESS_SCOPE = f"access:services!service={SERVICE_NAME}"

# JupyterHub 6's default `server` role: what a server token (JUPYTERHUB_API_TOKEN) holds.
_SERVER_DEFAULT = ("users:activity!user", "access:servers!server")


def service_command(python: str, db_path: Path) -> list[str]:
    """Return the service's command line: `python -m course_lib.hub.progress --db db_path`."""
    return [python, "-m", "course_lib.hub.progress", "--db", str(db_path)]


def service_spec(port: int, api_token: str) -> dict[str, Any]:
    """Return the entry for `c.JupyterHub.services`: the progress service, external.

    The hub proxies /services/course-progress/ to http://127.0.0.1:port, trusts `api_token`
    as the service's and gives it an OAuth client (`service-course-progress`). The hub does
    not start it: JupyterHub hands a managed service no socket, and the service must get the
    one its launcher bound (no port race). `oauth_no_confirm`: the page is part of the
    course, so an admin is not asked to authorise it. `display`: the hub's home page lists it
    for admins to click.
    """
    return {
        "name": SERVICE_NAME,
        "url": f"http://127.0.0.1:{port}",
        "api_token": api_token,
        "oauth_no_confirm": True,
        "display": True,
    }


def service_environment(port: int, api_token: str, hub_api_url: str) -> dict[str, str]:
    """Return what JupyterHub would give the service, had it started it (HubOAuth reads it)."""
    prefix = f"/services/{SERVICE_NAME}/"
    return {
        "JUPYTERHUB_SERVICE_NAME": SERVICE_NAME,
        "JUPYTERHUB_SERVICE_URL": f"http://127.0.0.1:{port}",
        "JUPYTERHUB_SERVICE_PREFIX": prefix,
        "JUPYTERHUB_BASE_URL": "/",
        "JUPYTERHUB_API_URL": hub_api_url,
        "JUPYTERHUB_API_TOKEN": api_token,
        "JUPYTERHUB_CLIENT_ID": f"service-{SERVICE_NAME}",
        "JUPYTERHUB_OAUTH_CALLBACK_URL": f"{prefix}oauth_callback",
    }


def roles() -> list[dict[str, Any]]:
    """Return the entries for `c.JupyterHub.load_roles` the progress service needs.

    - `course-progress-service` (held by the service): `list:users` and `read:users:name`,
      so the page has a row for every learner the hub knows and can tell admins apart.
    - `user` (every user; JupyterHub's default `self` kept): also `access:services!service=
      course-progress`, so a learner's own tokens may reach the service at all. Reaching it
      is not seeing it: the page checks that the user is an admin, and a record is accepted
      only for the token's owner.
    - `server` (the scopes of every server token, JUPYTERHUB_API_TOKEN, the one kernels
      inherit): JupyterHub's default two scopes plus the same access scope, so a self-check
      in a learner's kernel can post. A server token gets only the scopes its owner holds,
      which is why the `user` role above must hold the access scope as well.
    """
    return [
        {
            "name": "course-progress-service",
            "description": "The course-progress service lists the hub's users",
            "scopes": ["list:users", "read:users:name"],
            "services": [SERVICE_NAME],
        },
        {
            "name": "user",
            "description": "Standard user privileges, and posting to course-progress",
            "scopes": ["self", ACCESS_SCOPE],
        },
        {
            "name": "server",
            "description": "Post activity, and the lessons' self-checks to course-progress",
            "scopes": [*_SERVER_DEFAULT, ACCESS_SCOPE],
        },
    ]
