"""Lesson 11's parameter panel: widgets built from a node's descriptors, like rqt_reconfigure.

Sliders take the declared range and step, read-only parameters are shown disabled, every
change prints the equivalent `ros2 param set` command, changes made elsewhere (a `%ros2` cell,
a terminal, the node itself) arrive through /parameter_events, and Save writes a params file.

The panel follows its node's life (`node_life`): while the node is gone it says so in one
line, with how to start it again, and its controls and Save are disabled (a change or a save
asked from code is refused with that line, never kept for later); when the node is back, the
panel reads every value and descriptor from it again.
"""

from __future__ import annotations

import html
import re
import threading
from pathlib import Path
from typing import Any

from ...core.errors import CourseError
from ...core.files.atomic_files import FileSaveError
from ...core.param_journal import acting_door
from .controls import control_for, refresh_control
from .events import changes_of, subscribe_parameter_events
from .node_life import (
    Identity,
    NodeNotRunningError,
    Stopped,
    graph_watch,
    start_command,
    stopped_now,
)
from .yaml_file import params_yaml, set_command, write_params_file

__all__ = ["RCLPY_BUILTINS", "ParameterPanel"]

# Declared by rclpy on every node; not the node's own settings, so the panel leaves them out.
RCLPY_BUILTINS = frozenset({"use_sim_time", "start_type_description_service"})
_CODE = re.compile(r"`([^`]+)`")


def _status_html(text: str) -> str:
    """Return one status line as HTML (a screen reader announces it), commands as code."""
    shown = _CODE.sub(r"<code>\1</code>", html.escape(text))
    return f'<span role="status" aria-live="polite">{shown}</span>' if text else ""


class ParameterPanel:
    """A panel of one node's parameters, kept in sync with the node while it runs."""

    def __init__(self, node: str, *, save_path: str | Path, session: Any = None) -> None:
        import ipywidgets as widgets

        from ...session.session import get_session

        self.session = session or get_session()
        self.node = node if node.startswith("/") else "/" + node
        self.save_path = Path(save_path)
        self.commands: list[str] = []
        self._syncing = threading.local()
        self._lock = threading.Lock()
        self._closed = False
        self._stopped: Stopped | None = None  # set while the node is gone
        self._reading = False  # the node is back: its values are being read again
        self._gone_count = 0  # a reading started before the node went again is dropped
        self._watch = graph_watch(self.session)
        self._identity = self._watch.identity(self.node)  # before reading: a restart shows
        self.descriptors: dict[str, Any] = {}
        self.controls: dict[str, Any] = {}
        self._known: dict[str, Any] = {}  # the node's values, as last heard from it
        self._command = start_command(self.session, self.node)
        self._apply(*self._read())
        self.status = widgets.HTML("")
        self.log = widgets.Output(layout={"border": "1px solid #ddd", "min_height": "60px"})
        self.save_button = widgets.Button(description="Save params file", icon="save")
        self.save_button.on_click(lambda _b: self._save_clicked())
        self._title = widgets.HTML(f"<b>Parameters of {html.escape(self.node)}</b>")
        self.widget = widgets.VBox()
        self._lay_out()
        self._stop_listening = subscribe_parameter_events(self.session, self._on_event)
        self._stop_watching = self._watch.follow(self.node, self._on_look)

    # -- reading the node --------------------------------------------------------------------
    def _read(self) -> tuple[list[Any], dict[str, Any]]:
        """Return the node's descriptors (less rclpy's own) and values, asked from the node."""
        from ...ros2.api import nodes_and_params as api

        described = [d for d in api.param_describe(self.node) if d.name not in RCLPY_BUILTINS]
        return described, {d.name: api.param_get(self.node, d.name).value for d in described}

    def _apply(self, descriptors: list[Any], values: dict[str, Any]) -> None:
        """Show these descriptors and values: controls kept where they fit, made otherwise."""
        self._syncing.on = True
        try:
            for desc in descriptors:
                control = self.controls.get(desc.name)
                if control is None or not refresh_control(control, desc, values[desc.name]):
                    control = control_for(desc, values[desc.name])
                    control.observe(self._changed(desc.name), names="value")
                    self.controls[desc.name] = control
        finally:
            self._syncing.on = False
        names = [d.name for d in descriptors]
        self.controls = {name: self.controls[name] for name in names}
        self.descriptors = {d.name: d for d in descriptors}
        self._known = dict(values)

    def _lay_out(self) -> None:
        """Show the controls, enabled only while the node runs and its values are known."""
        live = self._stopped is None and not self._reading
        for name, control in self.controls.items():
            control.disabled = self.descriptors[name].read_only or not live
        self.save_button.disabled = not live
        children = (self._title, self.status, *self.controls.values(), self.save_button)
        if tuple(self.widget.children) != (*children, self.log):
            self.widget.children = (*children, self.log)

    # -- the node's life ---------------------------------------------------------------------
    def _on_look(self, identity: Identity) -> None:
        """Take a graph look-up (the session's executor): the node left, or came back.

        The controls change before the status line says so: what the line says is then true.
        """
        said = ""
        with self._lock:
            if self._closed:
                return
            if not identity:
                if self._stopped is not None:
                    return
                self._stopped = stopped_now(self.session, self.node, self._command)
                self._gone_count += 1
                said = self._stopped.line
            elif identity <= self._identity or self._reading:
                return
            else:  # back, or another node of that name (restarted between two look-ups)
                news = self._stopped is not None or self._replaced(identity)
                self._reading = True
                reading = (identity, self._gone_count, news)
                threading.Thread(target=self._read_again, args=reading, daemon=True).start()
        self._lay_out()
        if said:
            self.status.value = _status_html(said)

    def _replaced(self, identity: Identity) -> bool:
        """Return whether `identity` has publishers the node shown had not: a restart (not
        the first sight of a node just started, known by its name only until then)."""
        return bool(self._identity - {self.node.encode()}) and bool(identity - self._identity)

    def _read_again(self, identity: Identity, gone_count: int, news: bool) -> None:
        """Read every value and descriptor of the node that is back (a thread of its own:
        the session's executor answers the calls)."""
        from ...ros2.node.client import ServiceCallError

        try:
            descriptors, values = self._read()
            command = start_command(self.session, self.node)
        except (CourseError, ServiceCallError):
            descriptors = None  # gone again, or not answering yet: the next look-up retries
        said = ""
        with self._lock:
            self._reading = False
            fresh = gone_count == self._gone_count and not self._closed
            if descriptors is not None and fresh:
                self._identity, self._stopped, self._command = identity, None, command
                self._apply(descriptors, values)
                if news:
                    said = f"{self.node} is running again: the panel shows the values it holds."
        self._lay_out()
        if said:
            self.status.value = _status_html(said)

    def _on_event(self, msg: Any) -> None:
        if msg.node != self.node:
            return
        changes = changes_of(msg)
        if self._stopped is not None or any(c.kind == "new" for c in changes):
            self._watch.look()  # a node (re)declaring its parameters: back, or restarted
        for change in changes:
            if change.kind == "changed":
                self._known[change.name] = change.value
                self._show(change.name, change.value)

    # -- setting values ----------------------------------------------------------------------
    def _changed(self, name: str) -> Any:
        def handler(change: Any) -> None:
            if getattr(self._syncing, "on", False):
                return
            self.set(name, change["new"])

        return handler

    def set(self, name: str, value: Any) -> bool:
        """Set a parameter as the panel does: print the command, revert the widget if refused
        (a node that is not running refuses everything; nothing is kept for later)."""
        from ...ros2.api import nodes_and_params as api
        from ...ros2.node.client import ServiceCallError

        if isinstance(value, float):
            value = round(value, 6)
        command = set_command(self.node, name, value)
        stopped = self._stopped
        if stopped is not None:
            return self._refuse(name, f"Not set ({name} {value!r}): {stopped.line}")
        try:
            with acting_door("panel"):
                result = api.param_set(self.node, name, value)
        except (CourseError, ServiceCallError) as error:  # gone a moment ago: not seen yet
            self._watch.look()
            return self._refuse(name, f"$ {command}\nNot set: {str(error).splitlines()[0]}")
        self.commands.append(command)
        if not result.successful:
            self._known[name] = api.param_get(self.node, name).value
            return self._refuse(name, f"$ {command}\nSetting parameter failed: {result.reason}")
        self._known[name] = value
        self.log.append_stdout(f"$ {command}\nSet parameter successful\n")
        return True

    def _refuse(self, name: str, said: str) -> bool:
        """Log why a value was not set and show the node's own value again; return False."""
        self.log.append_stdout(f"{said}\n")
        self._show(name, self._known.get(name))
        return False

    def _show(self, name: str, value: Any) -> None:
        control = self.controls.get(name)
        if control is None or value is None or control.value == value:
            return
        self._syncing.on = True
        try:
            control.value = value
        finally:
            self._syncing.on = False

    # -- the node's values as a file ---------------------------------------------------------
    def _check_running(self) -> None:
        """Raise NodeNotRunningError if the node is gone (looked up again now: it may be back
        before the panel has seen it)."""
        stopped = self._stopped
        if stopped is not None and not self._watch.identity(self.node):
            raise NodeNotRunningError(stopped)

    def values(self) -> dict[str, Any]:
        """Return the node's current parameter values (asked from the node, not the widgets);
        NodeNotRunningError while the node is gone."""
        from ...ros2.api import nodes_and_params as api

        self._check_running()
        return {name: api.param_get(self.node, name).value for name in self.descriptors}

    def yaml(self) -> str:
        """Return the params file text for the node's current values."""
        return params_yaml(self.node, self.values())

    def save(self, path: str | Path | None = None) -> Path:
        """Write the node's current values as a `ros__parameters` YAML file, atomically;
        NodeNotRunningError (nothing written) while the node is gone."""
        return write_params_file(Path(path or self.save_path), self.node, self.values())

    def _save_clicked(self) -> None:
        from ...ros2.node.client import ServiceCallError

        try:
            path = self.save()
        except FileSaveError as error:  # a full disk: the old file is kept, and said so
            self.log.append_stdout(
                f"Not saved ({error.shown}): {error.reason}. {error.kept}\nTry: {error.hint}\n"
            )
            return
        except (CourseError, ServiceCallError) as error:  # said in the panel, never lost
            self.log.append_stdout(f"Not saved: {error}\n")
            return
        self.log.append_stdout(f"Saved {path.name}:\n{path.read_text()}")

    def _ipython_display_(self) -> None:
        from IPython.display import display

        display(self.widget)

    def close(self) -> None:
        """Stop following /parameter_events and the node's life (its graph look-ups)."""
        with self._lock:
            self._closed = True
        self._stop_watching()
        self._stop_listening()
