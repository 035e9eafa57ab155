"""A JupyterLab terminal driven through the server's REST and websocket API, from the page."""

from __future__ import annotations

import re
from typing import Any

from waits import POLL_MS

__all__ = ["Terminal"]

# Without a token (a hub's server signs in with a cookie) the request carries the XSRF header.
# Each terminal of the page is window.__terms[name]; window.__term is the latest one opened.
_OPEN = """async ([base, token]) => {
  const xsrf = (document.cookie.match(/(?:^|; )_xsrf=([^;]*)/) || [])[1] || '';
  const headers = token ? {} : {'X-XSRFToken': decodeURIComponent(xsrf)};
  const reply = await fetch(`${base}/api/terminals?token=${token}`, {method: 'POST', headers});
  const name = (await reply.json()).name;
  const term = {out: '', name};
  window.__terms = window.__terms || {};
  window.__terms[name] = term;
  window.__term = term;
  const url = `${base.replace('http', 'ws')}/terminals/websocket/${name}?token=${token}`;
  const ws = new WebSocket(url);
  ws.onmessage = (event) => {
    const [kind, text] = JSON.parse(event.data);
    if (kind === 'stdout') term.out += text;
  };
  await new Promise((resolve, reject) => { ws.onopen = resolve; ws.onerror = reject; });
  ws.send(JSON.stringify(['set_size', 50, 250, 1000, 2000]));  // as a wide terminal tab does
  term.ws = ws;
  return name;
}"""
# What `run_to_end` appends: the typed line shows `"=""=end $?"`, the shell prints `==end 0`.
_END = '; echo "=""=end $?"'
_ENDED = re.compile(r"==end (\d+)")


class Terminal:
    """One terminal of the lab server, as the learner opens it from the launcher."""

    def __init__(self, page: Any, base_url: str, token: str) -> None:
        self.page = page
        self.base_url, self.token = base_url, token
        self.name = page.evaluate(_OPEN, [base_url, token])

    @property
    def output(self) -> str:
        """Return everything the terminal printed so far."""
        return self.page.evaluate("(name) => window.__terms[name].out", self.name)

    def send(self, text: str) -> int:
        """Type `text` as is (no Enter); return how much the terminal had printed before."""
        start = len(self.output)
        self.page.evaluate(
            "([name, text]) => window.__terms[name].ws.send(JSON.stringify(['stdin', text]))",
            [self.name, text],
        )
        return start

    def wait_for(self, expect: str, start: int, timeout: float = 20.0, after: str = "") -> str:
        """Wait until `expect` shows in the output past `start`; return that output.

        Fail with what the terminal printed; `after` names what was typed, for that message.
        """
        from playwright.sync_api import TimeoutError as PlaywrightTimeout

        try:
            self.page.wait_for_function(
                "([name, start, expect]) =>"
                " window.__terms[name].out.slice(start).includes(expect)",
                arg=[self.name, start, expect],
                timeout=timeout * 1000,
                polling=POLL_MS,
            )
        except PlaywrightTimeout:
            raise AssertionError(
                f"the terminal never printed {expect!r} after {after or 'that'}; it printed:\n"
                f"{self.output[start:][-2000:]}"
            ) from None
        return self.output[start:]

    def run(self, command: str, expect: str, timeout: float = 20.0) -> str:
        """Type `command`, wait until `expect` follows it in the output; return that output."""
        start = self.send(command + "\r")
        return self.wait_for(expect, start, timeout, after=f"`{command}`")

    def run_to_end(self, command: str, timeout: float = 30.0) -> tuple[str, int]:
        """Run `command` until it ends; return what it printed after the typed line, and its
        exit code."""
        from playwright.sync_api import TimeoutError as PlaywrightTimeout

        start = self.send(command + _END + "\r")
        try:
            self.page.wait_for_function(
                r"([name, start]) => /==end \d+\r?\n/.test(window.__terms[name].out.slice(start))",
                arg=[self.name, start],
                timeout=timeout * 1000,
                polling=POLL_MS,
            )
        except PlaywrightTimeout:
            raise AssertionError(
                f"`{command}` did not end within {timeout:g} s; the terminal printed:\n"
                f"{self.output[start:][-2000:]}"
            ) from None
        printed = self.output[start:]
        ended = _ENDED.search(printed)
        assert ended is not None, printed
        typed = max(printed.rfind(_END.strip("; ")), 0)  # the typed line (readline may redraw it)
        body = printed[printed.find("\n", typed) + 1 : ended.start()]
        return body, int(ended[1])

    def close(self) -> None:
        """End the terminal's shell."""
        self.page.evaluate(
            "([base, name, token]) => {"
            " const xsrf = (document.cookie.match(/(?:^|; )_xsrf=([^;]*)/) || [])[1] || '';"
            " const headers = token ? {} : {'X-XSRFToken': decodeURIComponent(xsrf)};"
            " return fetch(`${base}/api/terminals/${name}?token=${token}`,"
            " {method: 'DELETE', headers}); }",
            [self.base_url, self.name, self.token],
        )
