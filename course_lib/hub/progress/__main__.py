"""`python -m course_lib.hub.progress --db FILE`: the progress service, as the hub runs it.

It reads what JupyterHub gives a service (JUPYTERHUB_API_TOKEN, JUPYTERHUB_API_URL,
JUPYTERHUB_SERVICE_URL, JUPYTERHUB_SERVICE_PREFIX, JUPYTERHUB_CLIENT_ID, ...) and serves until
SIGTERM or SIGINT: on the listening socket it inherited (`--listen-fd N`, the class hub's
launcher bound it), or else on the service URL's address (a pod of its own on Kubernetes).
"""

from __future__ import annotations

import argparse
import asyncio
import logging
import os
import secrets
import signal
import socket
import sys
from pathlib import Path
from urllib.parse import urlparse

from . import DB_ENV, SERVICE_NAME

_NEEDED = ("JUPYTERHUB_API_TOKEN", "JUPYTERHUB_API_URL", "JUPYTERHUB_SERVICE_URL")


def _arguments(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="python -m course_lib.hub.progress",
        description=f"The {SERVICE_NAME} JupyterHub service (the hub starts it).",
    )
    parser.add_argument(
        "--db", type=Path, default=os.environ.get(DB_ENV), help=f"the SQLite file (or ${DB_ENV})"
    )
    parser.add_argument(
        "--listen-fd", type=int, default=None, help="serve on this inherited listening socket"
    )
    args = parser.parse_args(argv)
    missing = [name for name in _NEEDED if not os.environ.get(name)]
    if missing:
        parser.error(
            f"{', '.join(missing)} not set: the hub runs this service and sets them "
            "(an entry of c.JupyterHub.services from course_lib.hub.progress.service_spec)."
        )
    if args.db is None:
        parser.error(f"no database: give --db FILE (or set {DB_ENV}).")
    return args


async def _serve(db: Path, listen_fd: int | None = None) -> None:
    from jupyterhub.services.auth import HubOAuth

    from ...lessons.catalogue import TITLES
    from .app import MAX_READ_BYTES, ServiceContext, make_app
    from .store import ProgressStore

    store = ProgressStore(db)
    auth = HubOAuth(cache_max_age=60)
    context = ServiceContext(store=store, auth=auth, titles=TITLES)
    prefix = os.environ.get("JUPYTERHUB_SERVICE_PREFIX", f"/services/{SERVICE_NAME}/")
    app = make_app(context, prefix, cookie_secret=secrets.token_bytes(32))
    address = urlparse(os.environ["JUPYTERHUB_SERVICE_URL"])
    if listen_fd is None:
        server = app.listen(
            address.port or 80, address.hostname or "127.0.0.1", max_body_size=MAX_READ_BYTES
        )
    else:  # bound by whoever started this: the port was never free for another to take
        from tornado.httpserver import HTTPServer

        listener = socket.socket(fileno=listen_fd)
        listener.setblocking(False)
        server = HTTPServer(app, max_body_size=MAX_READ_BYTES)
        server.add_sockets([listener])
    logging.getLogger(SERVICE_NAME).info(
        "serving %s on %s, records in %s", prefix, address.netloc, db
    )
    stopped = asyncio.Event()
    loop = asyncio.get_running_loop()
    for signum in (signal.SIGTERM, signal.SIGINT):
        loop.add_signal_handler(signum, stopped.set)
    try:
        await stopped.wait()
    finally:
        server.stop()
        store.close()


def main(argv: list[str] | None = None) -> int:
    """Run the service; return the exit code (2 and one sentence when it cannot start)."""
    args = _arguments(argv)
    logging.basicConfig(
        level=logging.WARNING, format=f"[%(levelname)s {SERVICE_NAME}] %(message)s"
    )
    logging.getLogger(SERVICE_NAME).setLevel(logging.INFO)
    from .store import StoreError

    try:
        asyncio.run(_serve(args.db, args.listen_fd))
    except StoreError as error:
        print(f"{SERVICE_NAME}: {error}", file=sys.stderr)
        return 2
    except OSError as error:  # the port is taken, most likely
        print(f"{SERVICE_NAME}: cannot listen on {os.environ['JUPYTERHUB_SERVICE_URL']}: "
              f"{error}", file=sys.stderr)  # fmt: skip
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
