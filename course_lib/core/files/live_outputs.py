"""Live outputs (the 3D view, widgets) are not stored: a saved notebook says how to see them.

A stored iframe of a viewer that is gone shows a 500 page, and a stored widget shows "model
not found". `make lab` installs `scrub_on_save` as the Jupyter server's pre-save hook, and
`make notebooks` applies `scrub_live_outputs` too, so a reopened notebook shows one plain
sentence instead. Pure code: works on notebook dicts.
"""

from __future__ import annotations

from typing import Any

__all__ = ["LIVE_MARK", "PLACEHOLDERS", "is_live", "placeholder", "scrub_live_outputs"]

LIVE_MARK = "data-course-live"  # attribute the course puts on its live HTML (the 3D view)
WIDGET_MIME = "application/vnd.jupyter.widget-view+json"
PLACEHOLDERS = {
    "view": "The live 3D view is not stored with the notebook: run this cell to see it.",
    "widget": "This live widget is not stored with the notebook: run this cell to see it.",
}


def _kind(output: dict[str, Any]) -> str | None:
    data = output.get("data") or {}
    if WIDGET_MIME in data:
        return "widget"
    html = data.get("text/html", "")
    if isinstance(html, list):
        html = "".join(html)
    return "view" if LIVE_MARK in html else None


def is_live(output: dict[str, Any]) -> bool:
    """Return True for an output that only works while its kernel runs."""
    return output.get("output_type") in ("display_data", "execute_result") and bool(_kind(output))


def placeholder(kind: str) -> dict[str, Any]:
    """Return the stored output that replaces a live one of `kind`."""
    return {
        "output_type": "display_data",
        "data": {"text/plain": PLACEHOLDERS[kind]},
        "metadata": {},
    }


def scrub_live_outputs(notebook: dict[str, Any]) -> int:
    """Replace every live output of `notebook` in place; return how many were replaced."""
    replaced = 0
    for cell in notebook.get("cells", []):
        outputs = cell.get("outputs")
        if not outputs:
            continue
        kept: list[Any] = []
        for output in outputs:
            kind = _kind(output) if is_live(output) else None
            if kind is None:
                kept.append(output)
                continue
            replaced += 1
            if placeholder(kind) not in kept:
                kept.append(placeholder(kind))
        cell["outputs"] = kept
    return replaced


def scrub_on_save(model: dict[str, Any], **_kwargs: Any) -> None:
    """Jupyter server pre-save hook: store placeholders instead of live outputs."""
    if model.get("type") == "notebook" and isinstance(model.get("content"), dict):
        scrub_live_outputs(model["content"])
