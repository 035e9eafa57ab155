"""A Jupyter server extension for test_lab_server.py: every program the server starts is logged.

Loaded with the server, it adds an audit hook that writes the command line of each process the
server starts (`subprocess.Popen`) as one JSON line to the file named by SPAWN_LOG_ENV.
"""

from __future__ import annotations

import json
import os
import sys
from typing import Any

SPAWN_LOG_ENV = "COURSE_TEST_SPAWN_LOG"


def _jupyter_server_extension_points() -> list[dict[str, str]]:
    return [{"module": "spawn_log"}]


def _load_jupyter_server_extension(serverapp: Any) -> None:
    path = os.environ[SPAWN_LOG_ENV]

    def log_spawn(event: str, args: tuple[Any, ...]) -> None:
        if event == "subprocess.Popen":
            argv = args[1]
            words = [argv] if isinstance(argv, (str, bytes)) else list(argv or ())
            with open(path, "a", encoding="utf-8") as out:
                out.write(json.dumps([os.fsdecode(word) for word in words]) + "\n")

    sys.addaudithook(log_spawn)
