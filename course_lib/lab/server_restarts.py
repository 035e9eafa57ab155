"""A lab's Jupyter server killed by a signal comes back at the same address.

The out-of-memory killer or a stray `kill` can end the Jupyter server alone. The open page
keeps the learner's unsaved edits and keeps trying its server: started again at the same port
with the same token, the server answers that page, which says it is connected again, and the
edits can be saved (the kernels died with the old server: JupyterLab starts new ones). The
killed server's runtime file (`jpserver-<pid>.json`, left behind by a kill) says its port and
token. A server that ends by itself (exit code 0 or 1, Ctrl-C, `make stop`) is not started
again, nor one killed again and again (RESTARTS_MAX within RESTARTS_WINDOW_S).
"""

from __future__ import annotations

import json
import signal
import sys
import time
from collections.abc import Mapping, Sequence
from pathlib import Path

__all__ = [
    "RESTARTS_MAX",
    "RESTARTS_WINDOW_S",
    "ServerRestarts",
    "argv_with",
    "runtime_file",
]

RESTARTS_MAX = 3
RESTARTS_WINDOW_S = 60.0


# The options a restart sets: the first server's own (given or chosen) give way to them, as
# the server refuses an option given twice.
_REPLACED = (
    "--ServerApp.port=",
    "--port=",
    "--ServerApp.port_retries=",
    "--port-retries=",
    "--IdentityProvider.token=",
    "--ServerApp.token=",
    "--ServerApp.open_browser=",
)
_REPLACED_FLAGS = ("--no-browser", "--browser")


def argv_with(argv: Sequence[str], options: Sequence[str]) -> list[str]:
    """Return the server's command line `argv` with `options` in place of its own."""
    kept = [arg for arg in argv if not arg.startswith(_REPLACED) and arg not in _REPLACED_FLAGS]
    return [*kept, *options]


def runtime_dir(env: Mapping[str, str]) -> Path:
    """Return the Jupyter runtime folder of a server started with `env`."""
    from jupyter_core.paths import jupyter_runtime_dir

    return Path(env.get("JUPYTER_RUNTIME_DIR") or jupyter_runtime_dir())


def runtime_file(env: Mapping[str, str], pid: int) -> Path:
    """Return the runtime file a Jupyter server of pid `pid` writes (its port, token, url)."""
    return runtime_dir(env) / f"jpserver-{pid}.json"


class ServerRestarts:
    """Decide whether a lab's ended server starts again, and with what options."""

    def __init__(self, env: Mapping[str, str]) -> None:
        self._env = env
        self._times: list[float] = []

    def argv_again(self, pid: int, code: int | None) -> list[str] | None:
        """Return the options that start the server of `pid`, ended with `code`, again at its
        address; None when it ended by itself, was killed too often, or left no address."""
        if code is None or code >= 0:
            return None
        if -code in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            return None  # asked to stop: Ctrl-C, `make stop`, a closed terminal
        now = time.monotonic()
        self._times = [t for t in self._times if now - t < RESTARTS_WINDOW_S]
        if len(self._times) >= RESTARTS_MAX:
            self._say(f"it was killed {RESTARTS_MAX + 1} times within a minute: not again")
            return None
        found = runtime_file(self._env, pid)
        try:
            info = json.loads(found.read_text(encoding="utf-8"))
            port, token = int(info["port"]), str(info["token"])
        except (OSError, ValueError, KeyError, TypeError):
            self._say(f"its address is unknown ({found} unreadable): run `make lab` again")
            return None
        for left in (found, found.with_name(f"jpserver-{pid}-open.html")):
            left.unlink(missing_ok=True)
        self._times.append(now)
        self._say(
            f"it was killed (signal {-code}); starting it again at {info.get('url', port)}: "
            "your open pages connect again, and what you typed since the last save can be "
            "saved there (File > Save). Kernels start afresh: run your lessons' cells again."
        )
        return [
            f"--ServerApp.port={port}",
            "--ServerApp.port_retries=0",
            f"--IdentityProvider.token={token}",
            "--ServerApp.open_browser=False",
        ]

    @staticmethod
    def _say(text: str) -> None:
        print(f"The lab's Jupyter server ended: {text}", file=sys.stderr, flush=True)
