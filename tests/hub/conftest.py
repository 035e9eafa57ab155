"""One real JupyterHub per test module (its proxy from npm, installed once per run)."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from progress_hub import ClassHub, proxy_command


@pytest.fixture(scope="session")
def proxy(tmp_path_factory: pytest.TempPathFactory) -> str:
    """Return configurable-http-proxy, installed from npm once (shared by xdist workers)."""
    shared = tmp_path_factory.getbasetemp().parent  # the same folder for every worker
    return proxy_command(shared / "configurable-http-proxy")


@pytest.fixture(scope="module")
def hub(tmp_path_factory: pytest.TempPathFactory, proxy: str) -> Iterator[ClassHub]:
    """Yield a running hub with the progress service, three learners and one admin."""
    class_hub = ClassHub(tmp_path_factory.mktemp("hub"), proxy)
    class_hub.start()
    try:
        yield class_hub
    finally:
        class_hub.close()
