"""The class hub starts its proxy with the course's preload (keep-alive to Unix sockets)."""

from __future__ import annotations

from pathlib import Path

from traitlets.config import Config

from course_lib.hub.hub_config import configure
from course_lib.hub.plan import HubPlan
from course_lib.hub.proxy import PINS_DIR, PRELOAD, proxy_command


def test_the_hub_runs_its_proxy_with_the_unix_keepalive_preload(tmp_path: Path) -> None:
    command = proxy_command(tmp_path / "environment")
    plan = HubPlan(
        ip="127.0.0.1",
        port=8000,
        hub_port=8081,
        proxy_api_port=8001,
        progress_port=8090,
        authenticator="pam",
        learners=("alice",),
        admins=(),
        state=str(tmp_path / "state"),
        course=str(tmp_path / "course"),
        proxy_command=str(command),
        idle_minutes=60,
    )
    c = Config()
    configure(c, plan)
    argv = c.ConfigurableHTTPProxy.command
    # python -m course_lib.hub.tied --parent PID, then node --import <preload> <proxy>
    assert argv[1:3] == ["-m", "course_lib.hub.tied"]
    assert argv[-3:] == ["--import", (command.parents[2] / PRELOAD).as_uri(), str(command)]
    assert Path(argv[-4]).name == "node"
    assert (PINS_DIR / PRELOAD).is_file()  # install_proxy copies it beside node_modules/
