"""Fixtures of the browser tests: Debian's chromium through Playwright, and a course JupyterLab."""

from __future__ import annotations

import os
import shutil
from collections.abc import Iterator, Sequence
from pathlib import Path

import pytest
from browser_path import INSTALL_HINT, find_chromium
from cpu_by_test import count_apart
from lab_server import ARTIFACTS, LabServer

CHROMIUM = find_chromium()
FLAGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--enable-unsafe-swiftshader",  # WebGL (the meshcat view) in software
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


_PREBUILD: list[object] = []  # the learners' environment's build, started at collection


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Skip browser tests, saying how to enable them, where chromium is missing; start
    building the class hub's environment at once if its test is to run (minutes, mostly
    pip, that then overlap the other tests)."""
    if CHROMIUM is not None:
        hub_test = any(item.path.name == "test_class_hub.py" for item in items)
        # every worker collects every test: the first worker alone builds (the others' builds
        # only waited for its lock, about 2 CPU-s each)
        first = os.environ.get("PYTEST_XDIST_WORKER", "gw0") == "gw0"
        if hub_test and first and os.geteuid() == 0 and not _PREBUILD:
            from class_hub import start_prebuild

            build = start_prebuild()
            _PREBUILD.append(build)
            # no test's CPU: the CPU table names it, instead of charging this worker's first test
            count_apart(build.pid, "tests/browser/class_hub.py::the learners' environment build")
        return
    skip = pytest.mark.skip(reason=INSTALL_HINT)
    for item in items:
        if "browser" in item.keywords:
            item.add_marker(skip)


@pytest.fixture(scope="module")
def browser() -> Iterator[object]:
    """Yield a headless Debian chromium driven by Playwright (never a downloaded browser)."""
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        chromium = playwright.chromium.launch(executable_path=CHROMIUM, headless=True, args=FLAGS)
        try:
            yield chromium
        finally:
            chromium.close()


@pytest.fixture
def artifacts(request: pytest.FixtureRequest) -> Path:
    """Return this test's folder for screenshots (gitignored), empty; what the test's earlier
    attempt left there (a rerun's failed one, or the last run's) is kept as `<name>.previous`."""
    folder = ARTIFACTS / request.node.name
    _keep_as_previous(folder)
    folder.mkdir(parents=True)
    return folder


def _keep_as_previous(folder: Path) -> None:
    """Move `folder`, if there, to `<folder>.previous` (replacing an older one)."""
    if folder.exists():
        previous = folder.with_name(folder.name + ".previous")
        shutil.rmtree(previous, ignore_errors=True)
        folder.rename(previous)


@pytest.fixture(scope="module")
def lab(request: pytest.FixtureRequest) -> Iterator[LabServer]:
    """Start a course JupyterLab on copies of the module's LESSONS."""
    server = _learners_lab(ARTIFACTS / f"lab-{request.module.__name__}", request.module.LESSONS)
    try:
        yield server
    finally:
        server.stop()


def _learners_lab(root: Path, lessons: list[str], extra: Sequence[str] = ()) -> LabServer:
    """Start a lab on copies of `lessons` laid out as a learner's copy on a hub is:
    `notebooks/` with its own `my_files/` (what the lessons write, and what a relative path in
    a command finds), `rosject` beside it. Never the repository's own `notebooks/my_files/`.
    The last lab in `root` (a rerun's failed attempt, with its lab.log) is kept beside it as
    `<root>.previous` (ci55 lost the log of a lab whose kernels showed "Disconnected")."""
    from suite_env import independent_env

    from course_lib.core.paths import LEARNER_ROOT_ENV, ROSJECT_DIR

    _keep_as_previous(root)
    (root / "notebooks" / "my_files").mkdir(parents=True)
    (root / "rosject").symlink_to(ROSJECT_DIR, target_is_directory=True)
    env = independent_env(**{LEARNER_ROOT_ENV: str(root)})
    return LabServer(lessons, root / "notebooks", env=env, extra=extra)


@pytest.fixture(scope="module")
def page(browser, lab, request: pytest.FixtureRequest):  # type: ignore[no-untyped-def]
    """One browser tab on the module's first lesson, shared by its tests (they run in order)."""
    tab = browser.new_page(viewport={"width": 1280, "height": 1000})
    tab.goto(lab.lab_url(request.module.LESSONS[0]))
    yield tab
    tab.close()


def _run_suffix() -> str:
    """Return "-<pid>" for a walk run by hand (`make chaos`, `make soak`), else ""."""
    by_hand = os.environ.get("CHAOS_FAULTS") or os.environ.get("WALK_SOAK")
    return f"-{os.getpid()}" if by_hand else ""


@pytest.fixture
def lab_page(browser, request: pytest.FixtureRequest) -> Iterator[object]:  # type: ignore[no-untyped-def]
    """A lab of its own for each attempt (a rerun inherits nothing) on copies of the module's
    LESSONS, laid out as a learner's copy on a hub is (`notebooks/`, `rosject` beside it, their
    own `my_files/`), and one browser tab on it with the file browser on the lessons."""
    from lab_ui import LabPage

    server = _learners_lab(
        # two `make chaos` at once: a lab folder each (the lessons' copies are rewritten)
        ARTIFACTS / f"lab-{request.node.name}{_run_suffix()}",
        request.module.LESSONS,
        extra=["--LabApp.expose_app_in_browser=True"],  # the tests read cells from the model
    )
    try:
        tab = browser.new_page(viewport={"width": 1280, "height": 1000})
        try:
            yield LabPage(tab, server)
        finally:
            tab.close()
    finally:
        server.stop()


@pytest.fixture(scope="session")
def axe_js(tmp_path_factory: pytest.TempPathFactory) -> str:
    """Return axe-core's script, installed from npm once per run (shared by the workers)."""
    from accessibility import axe_source

    return axe_source(tmp_path_factory.getbasetemp().parent / "axe-core")
