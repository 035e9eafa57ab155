"""The page of turtlesim's window: the SVG, fetched again five times a second (pure)."""

from __future__ import annotations

__all__ = ["REFRESH_MS", "window_page"]

REFRESH_MS = 200

_PAGE = """<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>TurtleSim</title>
<style>
  body {{ margin: 0; padding: 12px; font-family: sans-serif; background: #f4f4f4; }}
  #window {{ width: 500px; height: 500px; box-shadow: 0 1px 4px #888; }}
  #status {{ margin-top: 6px; color: #555; font-size: 13px; }}
</style>
</head>
<body>
<div id="window">{svg}</div>
<div id="status">TurtleSim: {node}</div>
<script>
const view = document.getElementById("window");
const status = document.getElementById("status");
async function refresh() {{
  try {{
    const reply = await fetch("view.svg", {{cache: "no-store"}});
    if (reply.ok) {{
      view.innerHTML = await reply.text();
      status.textContent = "TurtleSim: {node}";
    }}
  }} catch (error) {{
    status.textContent = "turtlesim_node is not running: start it again, then reload this page.";
  }}
  setTimeout(refresh, {refresh_ms});
}}
setTimeout(refresh, {refresh_ms});
</script>
</body>
</html>
"""


def window_page(svg: str, node: str) -> str:
    """Return the page showing `svg` now and refreshing it from `view.svg`."""
    return _PAGE.format(svg=svg, node=node, refresh_ms=REFRESH_MS)
