"""A stand-in for a learner's single-user server, started by a real hub's spawner.

It keeps what the hub gave it (its server token and the progress URL, in a file only root
reads) and answers every GET, which is all the hub asks of a server to call it running. The
tests then act as that server's kernels would, with that very token.
"""

from __future__ import annotations

import contextlib
import http.server
import json
import os
import sys
from pathlib import Path
from urllib.parse import urlparse

KEPT = (
    "JUPYTERHUB_API_TOKEN",
    "JUPYTERHUB_USER",
    "COURSE_PROGRESS_URL",
    "COURSE_PROGRESS_HOLDER_UID",
    "JUPYTERHUB_API_URL",
)


class _Up(http.server.BaseHTTPRequestHandler):
    def do_GET(self) -> None:
        self.send_response(200)
        self.send_header("Content-Type", "text/plain")
        self.end_headers()
        self.wfile.write(b"fake single-user server\n")

    def log_message(self, *args: object) -> None:  # quiet
        pass


def main() -> int:
    out = Path(os.environ["FAKE_SERVER_OUT"]) / f"{os.environ['JUPYTERHUB_USER']}.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    partial = out.with_suffix(".part")
    partial.write_text(json.dumps({k: os.environ.get(k, "") for k in KEPT}))
    partial.chmod(0o600)
    partial.replace(out)
    address = urlparse(os.environ["JUPYTERHUB_SERVICE_URL"])
    server = http.server.HTTPServer((address.hostname or "127.0.0.1", address.port), _Up)
    with contextlib.suppress(KeyboardInterrupt):  # the hub stops a server with SIGINT
        server.serve_forever()
    return 0


if __name__ == "__main__":
    sys.exit(main())
