"""The hub's proxy passes requests with a body on to a server on a Unix socket, every time.

A learner's server behind the wall listens on a Unix socket. configurable-http-proxy sent
each request to such a target on a connection of its own, which the server closes once it has
answered; a write of the proxy's still pending then failed (EPIPE) and the learner got a 503
for a request the server had carried out: "Error Starting Kernel: 503 Service Unavailable" in
a class-hub browser test, and in 24 of 400 PATCH requests here. The course's proxy command
(course_lib/hub/provision/proxy.py: proxy_argv) gives such targets a keep-alive agent.
"""

from __future__ import annotations

import json
import shutil
import sys
from pathlib import Path
from urllib.parse import quote

import pytest
import requests
from suite_env import independent_env

from course_lib.core.host.ports import free_port
from course_lib.core.waiting import wait_until
from course_lib.hub.provision.proxy import proxy_argv
from course_lib.processes.children import spawn

pytestmark = [
    pytest.mark.slow,
    pytest.mark.skipif(shutil.which("npm") is None, reason="npm installs the hub's proxy"),
]

REQUESTS = 400
TOKEN = "proxy-unix-test-token"
# a Jupyter-like server (tornado) on a Unix socket: answers a PATCH once it has read its body
SERVER = """\
import asyncio, json, sys
import tornado.httpserver, tornado.netutil, tornado.web

class Sessions(tornado.web.RequestHandler):
    def patch(self, _):
        self.write({"path": json.loads(self.request.body)["path"]})

async def main():
    server = tornado.httpserver.HTTPServer(tornado.web.Application([(r"/(.*)", Sessions)]))
    server.add_socket(tornado.netutil.bind_unix_socket(sys.argv[1]))
    print("listening", flush=True)
    await asyncio.Event().wait()

asyncio.run(main())
"""


def test_requests_with_a_body_reach_a_unix_socket_server_through_the_proxy(
    proxy: str, tmp_path: Path
) -> None:
    socket_path = tmp_path / "server.sock"
    server = spawn([sys.executable, "-c", SERVER, str(socket_path)], name="unix-server")
    port, api_port = free_port(), free_port()
    argv = [
        *proxy_argv(proxy),
        *("--ip", "127.0.0.1", "--port", str(port)),
        *("--api-ip", "127.0.0.1", "--api-port", str(api_port)),
    ]
    env = independent_env(CONFIGPROXY_AUTH_TOKEN=TOKEN)
    chp = spawn(argv, name="proxy", env=env, merge_stderr=True)
    try:
        assert server.wait_for_line("listening", 30.0), server.text()
        api = f"http://127.0.0.1:{api_port}/api/routes"
        headers = {"Authorization": f"token {TOKEN}"}

        def route_added() -> bool:
            target = f"http+unix://{quote(str(socket_path), safe='')}"
            try:
                answer = requests.post(
                    f"{api}/user/a", json={"target": target}, headers=headers, timeout=5
                )
            except requests.ConnectionError:
                return False
            return answer.status_code == 201

        assert wait_until(route_added, 30.0), chp.text()
        failed = []
        with requests.Session() as browser:  # one keep-alive connection, as a browser tab's
            for number in range(REQUESTS):
                path = f"notebooks/lesson_{number}.ipynb"
                answer = browser.patch(
                    f"http://127.0.0.1:{port}/user/a/api/sessions/{number}",
                    data=json.dumps({"path": path}),
                    headers={"Content-Type": "application/json"},
                    timeout=30,
                )
                if answer.status_code != 200 or answer.json() != {"path": path}:
                    failed.append(answer.status_code)
        log = chp.text()[-2000:]
        assert not failed, f"{len(failed)} of {REQUESTS} failed: {failed[:10]}\n{log}"
    finally:
        chp.stop(timeout=5.0)
        server.stop(timeout=5.0)
