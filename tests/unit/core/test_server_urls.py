"""Where the learner's browser finds a file the course's Jupyter server serves raw."""

from __future__ import annotations

from pathlib import Path

from course_lib.core.server_urls import SERVER_ROOT_ENV, jupyter_base_url, served_file_url


def test_a_file_in_the_served_folder_is_linked_under_files(tmp_path: Path) -> None:
    page = tmp_path / "notebooks" / "my_files" / "replays" / "lesson07 run.html"
    env = {SERVER_ROOT_ENV: str(tmp_path)}
    assert served_file_url(page, env) == "/files/notebooks/my_files/replays/lesson07%20run.html"
    hub = {**env, "JUPYTERHUB_SERVICE_PREFIX": "/user/ada/"}
    assert served_file_url(page, hub) == (
        "/user/ada/files/notebooks/my_files/replays/lesson07%20run.html"
    )


def test_no_link_outside_a_server_or_its_folder(tmp_path: Path) -> None:
    page = tmp_path / "replay.html"
    assert served_file_url(page, {}) is None  # a plain kernel, nbval: no server
    assert served_file_url(page, {SERVER_ROOT_ENV: str(tmp_path / "other")}) is None


def test_the_base_url_always_ends_with_one_slash() -> None:
    assert jupyter_base_url({}) == "/"
    assert jupyter_base_url({"JUPYTERHUB_SERVICE_PREFIX": "/user/ada"}) == "/user/ada/"
    assert jupyter_base_url({"COURSE_JUPYTER_BASE_URL": "/course/"}) == "/course/"
