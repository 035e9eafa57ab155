"""Lesson 11's parameter panel: widgets built from a node's descriptors, like rqt_reconfigure.

Sliders take the declared range and step, read-only parameters are shown disabled, every
change prints the equivalent `ros2 param set` command, changes made elsewhere (a `%ros2` cell,
a terminal, the node itself) arrive through /parameter_events, and Save writes a params file.
"""

from __future__ import annotations

import threading
from pathlib import Path
from typing import Any

from ...core.param_journal import acting_door
from ...ros2.values import BOOL, DOUBLE, INTEGER
from .events import changes_of, subscribe_parameter_events
from .yaml_file import params_yaml, set_command, write_params_file

__all__ = ["ParameterPanel"]


def _widget_for(desc: Any, value: Any) -> Any:
    """Return the ipywidget for one parameter, from its descriptor."""
    import ipywidgets as widgets

    common = {
        "description": desc.name,
        "disabled": desc.read_only,
        "tooltip": desc.description,
        "style": {"description_width": "110px"},
        "continuous_update": False,
    }
    rng = desc.range
    if desc.type == DOUBLE and rng is not None:
        step = rng.step or (rng.to_value - rng.from_value) / 100
        return widgets.FloatSlider(
            value=value,
            min=rng.from_value,
            max=rng.to_value,
            step=step,
            readout_format=".2f",
            **common,
        )
    if desc.type == INTEGER and rng is not None:
        return widgets.IntSlider(
            value=value, min=rng.from_value, max=rng.to_value, step=rng.step or 1, **common
        )
    if desc.type == DOUBLE:
        return widgets.FloatText(value=value, **common)
    if desc.type == INTEGER:
        return widgets.IntText(value=value, **common)
    if desc.type == BOOL:
        common.pop("continuous_update")
        return widgets.Checkbox(value=value, **common)
    return widgets.Text(value=str(value), **common)


# Declared by rclpy on every node; not the node's own settings, so the panel leaves them out.
RCLPY_BUILTINS = frozenset({"use_sim_time", "start_type_description_service"})


class ParameterPanel:
    """A panel of one node's parameters, kept in sync with the node."""

    def __init__(self, node: str, *, save_path: str | Path, session: Any = None) -> None:
        import ipywidgets as widgets

        from ...ros2.api import nodes_and_params as api
        from ...session.session import get_session

        self.session = session or get_session()
        self.node = node if node.startswith("/") else "/" + node
        self.save_path = Path(save_path)
        self.commands: list[str] = []
        self._syncing = threading.local()
        descriptors = [d for d in api.param_describe(self.node) if d.name not in RCLPY_BUILTINS]
        self.descriptors = {d.name: d for d in descriptors}
        self.controls: dict[str, Any] = {}
        for desc in descriptors:
            control = _widget_for(desc, api.param_get(self.node, desc.name).value)
            control.observe(self._changed(desc.name), names="value")
            self.controls[desc.name] = control
        self.log = widgets.Output(layout={"border": "1px solid #ddd", "min_height": "60px"})
        self.save_button = widgets.Button(description="Save params file", icon="save")
        self.save_button.on_click(lambda _b: self._save_clicked())
        title = widgets.HTML(f"<b>Parameters of {self.node}</b>")
        self.widget = widgets.VBox([title, *self.controls.values(), self.save_button, self.log])
        self._stop_listening = subscribe_parameter_events(self.session, self._on_event)

    def _changed(self, name: str) -> Any:
        def handler(change: Any) -> None:
            if getattr(self._syncing, "on", False):
                return
            self.set(name, change["new"])

        return handler

    def set(self, name: str, value: Any) -> bool:
        """Set a parameter as the panel does: print the command, revert the widget if refused."""
        from ...ros2.api import nodes_and_params as api

        if isinstance(value, float):
            value = round(value, 6)
        command = set_command(self.node, name, value)
        with acting_door("panel"):
            result = api.param_set(self.node, name, value)
        answer = (
            "Set parameter successful"
            if result.successful
            else (f"Setting parameter failed: {result.reason}")
        )
        self.commands.append(command)
        self.log.append_stdout(f"$ {command}\n{answer}\n")
        if not result.successful:
            self._show(name, api.param_get(self.node, name).value)
        return result.successful

    def _show(self, name: str, value: Any) -> None:
        control = self.controls.get(name)
        if control is None or control.value == value:
            return
        self._syncing.on = True
        try:
            control.value = value
        finally:
            self._syncing.on = False

    def _on_event(self, msg: Any) -> None:
        for change in changes_of(msg):
            if change.node == self.node and change.kind == "changed":
                self._show(change.name, change.value)

    def values(self) -> dict[str, Any]:
        """Return the node's current parameter values (asked from the node, not the widgets)."""
        from ...ros2.api import nodes_and_params as api

        return {name: api.param_get(self.node, name).value for name in self.descriptors}

    def yaml(self) -> str:
        """Return the params file text for the node's current values."""
        return params_yaml(self.node, self.values())

    def save(self, path: str | Path | None = None) -> Path:
        """Write the node's current values as a `ros__parameters` YAML file, atomically."""
        return write_params_file(Path(path or self.save_path), self.node, self.values())

    def _save_clicked(self) -> None:
        path = self.save()
        self.log.append_stdout(f"Saved {path.name}:\n{self.yaml()}")

    def _ipython_display_(self) -> None:
        from IPython.display import display

        display(self.widget)

    def close(self) -> None:
        """Stop following /parameter_events."""
        self._stop_listening()
