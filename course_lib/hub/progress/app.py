"""The service's web handlers: the admins' page and the records API, authenticated by the hub.

Who is asking always comes from the hub (JupyterHub's HubOAuth: a token in the
`Authorization` header, or the cookie an OAuth login left), never from the request's body.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass
from http import HTTPStatus
from typing import Any

from jupyterhub.services.auth import HubOAuth, HubOAuthCallbackHandler, HubOAuthenticated
from tornado import web

from ...lessons.progress.record import RecordError, parse_record
from . import SERVICE_NAME
from .hub_users import HubUsersError, hub_users
from .page import render_error, render_page
from .store import ProgressStore, StoreError

__all__ = ["Refusal", "ServiceContext", "make_app"]


MAX_BODY_BYTES = 4096  # a record is about 100 bytes; its `failed` sentence fits many times
MAX_READ_BYTES = 65536  # the server reads no more of any request (bigger: refused unread)


class Refusal(web.HTTPError):
    """An answer other than success, with a sentence for the body (not the status line)."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(status)
        self.message = message


def _message(status_code: int, kwargs: dict[str, Any]) -> str:
    error = kwargs.get("exc_info", (None, None, None))[1]
    said = getattr(error, "message", "") or getattr(error, "log_message", "")  # the hub's words
    return said or HTTPStatus(status_code).phrase


@dataclass(frozen=True)
class ServiceContext:
    """What every handler needs: the records, the hub's API and the lessons' titles."""

    store: ProgressStore
    auth: HubOAuth
    titles: Mapping[int, str]


class _HubHandler(HubOAuthenticated, web.RequestHandler):
    """A handler whose user the hub identifies."""

    def initialize(self, context: ServiceContext) -> None:
        self.context = context
        self.hub_auth = context.auth

    async def prepare(self) -> None:
        length = int(self.request.headers.get("Content-Length") or len(self.request.body))
        if length > MAX_BODY_BYTES:  # before asking the hub anything: nobody's record is that big
            raise Refusal(413, f"A record is at most {MAX_BODY_BYTES} bytes.")
        # Ask the hub once without blocking the loop; `current_user` then reads the cache.
        await self.hub_auth.get_user(self, sync=False)

    def _admin(self) -> dict[str, Any]:
        user = self.current_user
        if user is None or user.get("kind") != "user" or not user.get("admin"):
            raise Refusal(403, "Only the hub's admins see the class's progress.")
        return user


class PageHandler(_HubHandler):
    """GET /services/course-progress/: the page, admins only (others: login or 403)."""

    @web.authenticated
    async def get(self) -> None:
        self._admin()
        note = ""
        try:
            users = await hub_users(self.hub_auth.api_url, self.hub_auth.api_token)
        except HubUsersError as error:
            users, note = [], f"Only learners with records are shown: {error}."
        learners = [u.name for u in users if not u.admin]
        store = self.context.store
        html = render_page(
            learners,
            store.states(),
            titles=self.context.titles,
            note=note,
            exercises=store.exercise_stats(),
        )
        self.set_header("Cache-Control", "no-store")
        self.set_header("Content-Type", "text/html; charset=utf-8")
        self.finish(html)

    def write_error(self, status_code: int, **kwargs: Any) -> None:
        self.set_header("Content-Type", "text/html; charset=utf-8")
        self.finish(render_error(status_code, _message(status_code, kwargs)))


class RecordsHandler(_HubHandler):
    """POST: a learner's self-check, with their own token. GET: every record (admins)."""

    def get_login_url(self) -> str:
        raise Refusal(403, "Send a hub token.")  # an API answers, never redirects to a login

    def _owner(self) -> str:
        user = self.current_user
        if user is not None and user.get("kind") == "user":
            return str(user["name"])
        if user is None and not self.request.headers.get("Authorization"):
            self.set_header("WWW-Authenticate", "token")
            raise Refusal(401, "Send the learner's hub token: `Authorization: token <token>`.")
        raise Refusal(403, f"The hub does not let this token use {SERVICE_NAME}.")

    async def post(self) -> None:
        owner = self._owner()
        try:
            record = parse_record(self.request.body)
        except RecordError as error:
            raise Refusal(400, f"Bad record: {error}.") from None
        if record.user != owner:
            raise Refusal(403, f"This token is {owner}'s: it cannot post for {record.user!r}.")
        try:
            self.context.store.add(record)
        except StoreError as error:
            raise Refusal(500, str(error)) from None
        self.set_status(201)
        stored: dict[str, object] = {"user": record.user, "lesson": record.lesson}
        if record.exercise:
            stored.update(exercise=record.exercise, attempt=record.attempt)
        self.finish({"stored": stored})

    async def get(self) -> None:
        if self.current_user is None:
            self._owner()  # says 401 or 403
        self._admin()
        store = self.context.store
        self.finish(
            {
                "records": [s.as_json() for s in store.states()],
                "exercises": [s.as_json() for s in store.exercise_stats()],
            }
        )

    def write_error(self, status_code: int, **kwargs: Any) -> None:
        self.set_header("Content-Type", "application/json")
        self.finish(json.dumps({"status": status_code, "error": _message(status_code, kwargs)}))


class _CallbackHandler(HubOAuthCallbackHandler):
    """The end of the OAuth login (the hub sends the admin's browser here)."""

    def initialize(self, context: ServiceContext) -> None:
        self.hub_auth = context.auth


def make_app(context: ServiceContext, prefix: str, cookie_secret: bytes) -> web.Application:
    """Return the tornado application serving under `prefix` (/services/course-progress/)."""
    prefix = prefix.rstrip("/") + "/"
    args = {"context": context}
    return web.Application(
        [
            (prefix, PageHandler, args),
            (prefix.rstrip("/"), web.RedirectHandler, {"url": prefix}),
            (prefix + "oauth_callback", _CallbackHandler, args),
            (prefix + "api/records", RecordsHandler, args),
        ],
        cookie_secret=cookie_secret,
    )
