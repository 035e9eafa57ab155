"""Where the notebook's iframe points: through jupyter-server-proxy or directly (pure)."""

from __future__ import annotations

from course_lib.viz.viewer import viewer_url


def test_proxy_path_on_a_plain_jupyter_server() -> None:
    assert viewer_url(41000, "proxy", {}) == "/proxy/41000/static/"


def test_proxy_path_under_jupyterhub_prefix() -> None:
    env = {"JUPYTERHUB_SERVICE_PREFIX": "/user/ada/"}
    assert viewer_url(41000, "proxy", env) == "/user/ada/proxy/41000/static/"


def test_direct_address_when_asked() -> None:
    env = {"COURSE_VIEWER_URL": "direct"}
    assert viewer_url(41000, environ=env) == "http://127.0.0.1:41000/static/"


def test_auto_prefers_the_proxy_when_it_is_installed() -> None:
    assert viewer_url(41000, "auto", {}) == "/proxy/41000/static/"  # installed in the venv
