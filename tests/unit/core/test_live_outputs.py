"""Live outputs are replaced by one plain sentence when a notebook is stored (pure)."""

from __future__ import annotations

import copy

from course_lib.core.files.live_outputs import PLACEHOLDERS, scrub_live_outputs, scrub_on_save
from course_lib.viz.viewer import Viewer

WIDGET = {
    "output_type": "display_data",
    "data": {
        "application/vnd.jupyter.widget-view+json": {"model_id": "abc", "version_major": 2},
        "text/plain": "HBox(...)",
    },
    "metadata": {},
}
TEXT = {"output_type": "stream", "name": "stdout", "text": "Lesson 7\n"}
PLAIN_HTML = {
    "output_type": "display_data",
    "data": {"text/html": "<b>$ ros2 node list</b>", "text/plain": "/param_vel_node\n"},
    "metadata": {},
}


def _view() -> dict:
    html = Viewer(process=None, zmq_url="tcp://127.0.0.1:1", port=7001).iframe_html()
    return {"output_type": "display_data", "data": {"text/html": html}, "metadata": {}}


def _notebook(*outputs: dict) -> dict:
    return {"cells": [{"cell_type": "code", "source": "x", "outputs": list(outputs)}]}


def test_view_and_widget_become_placeholders_and_the_rest_is_kept() -> None:
    nb = _notebook(TEXT, _view(), WIDGET, PLAIN_HTML)
    assert scrub_live_outputs(nb) == 2
    outputs = nb["cells"][0]["outputs"]
    assert outputs[0] == TEXT and outputs[-1] == PLAIN_HTML
    assert [o["data"]["text/plain"] for o in outputs[1:3]] == [
        PLACEHOLDERS["view"],
        PLACEHOLDERS["widget"],
    ]


def test_a_notebook_without_live_outputs_is_unchanged() -> None:
    nb = _notebook(TEXT, PLAIN_HTML)
    before = copy.deepcopy(nb)
    assert scrub_live_outputs(nb) == 0
    assert nb == before


def test_scrubbing_twice_changes_nothing_more() -> None:
    nb = _notebook(WIDGET, WIDGET, _view())
    scrub_live_outputs(nb)
    once = copy.deepcopy(nb)
    assert scrub_live_outputs(nb) == 0
    assert nb == once
    assert len(nb["cells"][0]["outputs"]) == 2  # one sentence per kind, not one per widget


def test_save_hook_touches_only_notebooks() -> None:
    nb = _notebook(WIDGET)
    scrub_on_save({"type": "notebook", "content": nb}, path="x.ipynb")
    assert nb["cells"][0]["outputs"][0]["data"]["text/plain"] == PLACEHOLDERS["widget"]
    text = {"type": "file", "content": "data-course-live"}
    scrub_on_save(text, path="x.txt")
    assert text["content"] == "data-course-live"
