"""A JupyterLab terminal driven through the server's REST and websocket API, from the page."""

from __future__ import annotations

from typing import Any

__all__ = ["Terminal"]

# Without a token (a hub's server signs in with a cookie) the request carries the XSRF header.
_OPEN = """async ([base, token]) => {
  const xsrf = (document.cookie.match(/(?:^|; )_xsrf=([^;]*)/) || [])[1] || '';
  const headers = token ? {} : {'X-XSRFToken': decodeURIComponent(xsrf)};
  const reply = await fetch(`${base}/api/terminals?token=${token}`, {method: 'POST', headers});
  const name = (await reply.json()).name;
  window.__term = {out: '', name};
  const url = `${base.replace('http', 'ws')}/terminals/websocket/${name}?token=${token}`;
  const ws = new WebSocket(url);
  ws.onmessage = (event) => {
    const [kind, text] = JSON.parse(event.data);
    if (kind === 'stdout') window.__term.out += text;
  };
  await new Promise((resolve, reject) => { ws.onopen = resolve; ws.onerror = reject; });
  window.__term.ws = ws;
  return name;
}"""


class Terminal:
    """One terminal of the lab server, as the learner opens it from the launcher."""

    def __init__(self, page: Any, base_url: str, token: str) -> None:
        self.page = page
        self.base_url, self.token = base_url, token
        self.name = page.evaluate(_OPEN, [base_url, token])

    @property
    def output(self) -> str:
        """Return everything the terminal printed so far."""
        return self.page.evaluate("window.__term.out")

    def run(self, command: str, expect: str, timeout: float = 20.0) -> str:
        """Type `command`, wait until `expect` follows it in the output; return that output."""
        start = len(self.output)
        self.page.evaluate(
            "(text) => window.__term.ws.send(JSON.stringify(['stdin', text]))", command + "\r"
        )
        from playwright.sync_api import TimeoutError as PlaywrightTimeout

        try:
            self.page.wait_for_function(
                "([start, expect]) => window.__term.out.slice(start).includes(expect)",
                arg=[start, expect],
                timeout=timeout * 1000,
            )
        except PlaywrightTimeout:
            raise AssertionError(
                f"the terminal never printed {expect!r} after `{command}`; it printed:\n"
                f"{self.output[start:][-2000:]}"
            ) from None
        return self.output[start:]

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
