"""Signing in to a JupyterHub through its login form, as a browser does (with requests)."""

from __future__ import annotations

import re

import requests

__all__ = ["sign_in"]


def sign_in(
    hub_url: str, name: str, password: str, *, timeout: float = 30.0
) -> tuple[requests.Session, requests.Response]:
    """Post the login form as `name`; return the session (its cookies) and the page the hub
    sent it to last (following redirects: for a learner, the hub starts their server)."""
    session = requests.Session()
    form = session.get(f"{hub_url}/hub/login", timeout=30)
    xsrf = re.search(r'name="_xsrf" value="([^"]+)"', form.text)
    assert xsrf, form.text[:500]
    page = session.post(
        f"{hub_url}/hub/login",
        data={"username": name, "password": password, "_xsrf": xsrf.group(1)},
        timeout=timeout,
    )
    return session, page
