"""The image's doors that no test here can open: what Binder (repo2docker), a dev container
and a learner's `docker run` read from the repository. The image itself is built and run in
tests/browser/test_course_image.py."""

from __future__ import annotations

import json
import re
from pathlib import Path

from course_lib.tools.image_entry import IMAGE_PORT

REPO = Path(__file__).resolve().parents[3]
DOCKERFILE = (REPO / "Dockerfile").read_text()


def _instructions(word: str) -> list[str]:
    joined = re.sub(r"\\\n", " ", DOCKERFILE)
    return [
        line.strip()[len(word) :].strip()
        for line in joined.splitlines()
        if line.strip().upper().startswith(word + " ")
    ]


def test_binder_builds_the_course_as_uid_1000_from_its_build_arguments() -> None:
    # repo2docker builds the last stage, passing NB_USER and NB_UID (uid 1000 on Binder)
    assert _instructions("FROM")[-1] == "course"
    args = _instructions("ARG")
    assert "NB_USER=jovyan" in args and "NB_UID=1000" in args
    assert "USER ${NB_UID}" in DOCKERFILE
    assert f"EXPOSE {IMAGE_PORT}" in DOCKERFILE
    entry = json.loads(_instructions("ENTRYPOINT")[0])
    assert entry[0] == "tini" and entry[-3:] == ["-m", "course_lib", "image"]


def test_the_build_context_leaves_out_what_is_built_or_private() -> None:
    ignored = (REPO / ".dockerignore").read_text().splitlines()
    built = (".venv", "rosject/build", "rosject/install", ".pytest_cache")
    for path in (*built, "config/hub.yaml", ".git"):
        assert path in ignored, path


def test_the_dev_container_builds_the_image_and_forwards_the_labs_port() -> None:
    settings = json.loads((REPO / ".devcontainer" / "devcontainer.json").read_text())
    build = settings["build"]
    assert (REPO / ".devcontainer" / build["dockerfile"]).resolve() == REPO / "Dockerfile"
    assert settings["forwardPorts"] == [IMAGE_PORT]
    assert settings["overrideCommand"] is False  # the image's own command: the lab
    assert any("target=/home/jovyan" in mount for mount in settings["mounts"])


def test_the_readme_says_how_on_every_platform() -> None:
    readme = (REPO / "README.md").read_text()
    section = readme.split("## On macOS, Windows or another Linux", 1)[1].split("\n## ", 1)[0]
    assert "docker run --rm -p 8888:8888 -v ros2-course:/home/jovyan" in section
    for words in (
        "WSL 2",
        "Apple Silicon",
        "Raspberry Pi",
        "2.28",
        "mybinder.org",
        "devcontainer",
    ):
        assert words in section, words
