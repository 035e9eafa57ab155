"""One parameter's control in lesson 11's panel, built from its descriptor (ipywidgets, no ROS).

A ranged parameter gets a slider whose track gives each step at least one pixel (up to
MAX_TRACK_PX; a 300 px slider left `travel_time`'s 300 steps a 94 px track) and whose readout
shows the value rounded to the step.
"""

from __future__ import annotations

import math
from decimal import Decimal
from typing import Any

from ...ros2.results import Descriptor
from ...ros2.values import BOOL, DOUBLE, INTEGER

__all__ = [
    "LABEL_PX",
    "MAX_TRACK_PX",
    "MIN_TRACK_PX",
    "control_for",
    "readout_format",
    "refresh_control",
    "slider_width_px",
]

LABEL_PX = 110  # the parameter's name, left of the control
# What a slider row holds besides its label and track: the readout and the margins (a 300 px
# slider with a 110 px label had a 94 px track in JupyterLab 4).
READOUT_PX = 100
MIN_TRACK_PX = 300  # a short range still gets a track a mouse can aim along
MAX_PLACES = 6  # the panel sets values rounded to 6 decimals
MAX_TRACK_PX = 600  # wider rows no longer fit a notebook beside the prompt (the arrow keys step)


def _step(desc: Descriptor) -> float:
    rng = desc.range
    assert rng is not None
    if rng.step:
        return rng.step
    return 1 if desc.type == INTEGER else round((rng.to_value - rng.from_value) / 100, 9)


def readout_format(step: float) -> str:
    """Return the d3 format that shows a value rounded to `step` (0.1 -> '.1f', 1 -> 'd')."""
    exponent = Decimal(repr(float(step))).normalize().as_tuple().exponent
    places = min(max(0, -int(exponent)), MAX_PLACES)
    return f".{places}f"


def slider_width_px(desc: Descriptor) -> int:
    """Return the width of a slider row in which one step of `desc`'s range is at least 1 px."""
    rng = desc.range
    assert rng is not None
    steps = math.ceil(round((rng.to_value - rng.from_value) / _step(desc), 6))
    track = min(max(steps, MIN_TRACK_PX), MAX_TRACK_PX)
    return LABEL_PX + track + READOUT_PX


def _kind(desc: Descriptor) -> str:
    """Return the ipywidgets class name for `desc`."""
    ranged = desc.range is not None
    if desc.type == DOUBLE:
        return "FloatSlider" if ranged else "FloatText"
    if desc.type == INTEGER:
        return "IntSlider" if ranged else "IntText"
    return "Checkbox" if desc.type == BOOL else "Text"


def _traits(desc: Descriptor) -> dict[str, Any]:
    """Return what a control takes from `desc` (range, step, width, read-only, help)."""
    traits: dict[str, Any] = {"disabled": desc.read_only, "tooltip": desc.description}
    rng = desc.range
    if rng is not None and desc.type in (DOUBLE, INTEGER):
        step = _step(desc)
        traits |= {"min": rng.from_value, "max": rng.to_value, "step": step}
        if desc.type == DOUBLE:
            traits["readout_format"] = readout_format(step)
    return traits


def control_for(desc: Descriptor, value: Any) -> Any:
    """Return the ipywidget for one parameter, from its descriptor."""
    import ipywidgets as widgets

    kind = _kind(desc)
    options: dict[str, Any] = {
        "description": desc.name,
        "style": {"description_width": f"{LABEL_PX}px"},
    }
    if kind != "Checkbox":
        options["continuous_update"] = False
    if kind.endswith("Slider"):
        options["layout"] = {"width": f"{slider_width_px(desc)}px", "max_width": "100%"}
    if kind == "Text":
        value = str(value)
    return getattr(widgets, kind)(value=value, **options, **_traits(desc))


def refresh_control(control: Any, desc: Descriptor, value: Any) -> bool:
    """Give `control` the descriptor's range, step and read-only flag and the node's value, in
    place; return False if `desc` needs another kind of control."""
    if type(control).__name__ != _kind(desc):
        return False
    traits = _traits(desc) | {"value": str(value) if _kind(desc) == "Text" else value}
    with control.hold_trait_notifications():  # range and value checked together, at the end
        for name, new in traits.items():
            setattr(control, name, new)
    if _kind(desc).endswith("Slider"):
        control.layout.width = f"{slider_width_px(desc)}px"
    return True
