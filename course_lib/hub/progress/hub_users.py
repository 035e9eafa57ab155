"""Ask the hub's REST API (with the service's own token) which users it knows."""

from __future__ import annotations

import json
from dataclasses import dataclass

from tornado.httpclient import AsyncHTTPClient, HTTPClientError
from tornado.httputil import url_concat

__all__ = ["HubUser", "HubUsersError", "hub_users"]

_PAGINATED = "application/jupyterhub-pagination+json"
_PAGE = 200  # JupyterHub's largest page


class HubUsersError(RuntimeError):
    """The hub did not list its users: the message says why."""


@dataclass(frozen=True)
class HubUser:
    """A user of the hub: name, and whether an admin."""

    name: str
    admin: bool


async def _page(api_url: str, token: str, offset: int) -> dict:
    url = url_concat(api_url.rstrip("/") + "/users", {"offset": str(offset), "limit": str(_PAGE)})
    headers = {"Authorization": f"token {token}", "Accept": _PAGINATED}
    try:
        response = await AsyncHTTPClient().fetch(url, headers=headers, request_timeout=10)
    except HTTPClientError as error:
        raise HubUsersError(f"the hub answered {error.code} to GET {url}") from None
    except OSError as error:
        raise HubUsersError(f"cannot reach the hub at {api_url}: {error}") from None
    return json.loads(response.body)


async def hub_users(api_url: str, token: str) -> list[HubUser]:
    """Return every user the hub knows (all pages of `GET /hub/api/users`)."""
    users: list[HubUser] = []
    offset = 0
    while True:
        page = await _page(api_url, token, offset)
        items = page.get("items", [])
        users.extend(HubUser(u["name"], bool(u.get("admin"))) for u in items)
        following = (page.get("_pagination") or {}).get("next")
        if not following or not items:
            return users
        offset = int(following["offset"])
