"""`launch.actions.ExecuteProcess`: what to run; the runtime does the running."""

from __future__ import annotations

import os
import shlex
from dataclasses import dataclass, field
from typing import Any

from ..core.entity import Action
from ..core.event import BaseEventHandler
from ..core.event_handlers import OnProcessExit, OnShutdown
from ..core.events import SignalProcess
from ..core.substitution import normalize_to_list_of_substitutions, perform_substitutions
from .exposure import expose_action
from .substitutions import LaunchConfiguration

__all__ = ["ExecuteProcess", "ProcessSpec"]

OUTPUT_CHOICES = ("screen", "log", "both", "own_log", "full")


@dataclass
class ProcessSpec:
    """A process, fully resolved: ready to start."""

    name: str
    cmd: list[str]
    cwd: str | None
    env: dict[str, str]
    output: str | dict = "log"
    emulate_tty: bool = False
    shell: bool = False
    respawn: bool = False
    respawn_delay: float | None = None
    respawn_max_retries: int = -1
    sigterm_timeout: str = "5"  # as launch prints it in escalation messages
    sigkill_timeout: str = "10.0"  # seconds after SIGINT: sigterm + sigkill timeouts
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def cmd_text(self) -> str:
        """Return the command as launch prints it in 'process has died' messages."""
        return " ".join(part for part in self.cmd if part.strip())


def _truthy(text: str) -> bool:
    lowered = text.strip().lower()
    if lowered in ("true", "1"):
        return True
    if lowered in ("false", "0"):
        return False
    raise ValueError(f"Unknown boolean value '{text}' in condition expression")


@expose_action("executable")
class ExecuteProcess(Action):
    """Run a process; its output goes to the screen and/or the launch log."""

    @classmethod
    def parse(cls, entity: Any, parser: Any) -> Action:
        """`<executable cmd= name= ...>` (the process attributes `<node>` shares)."""
        return cls(
            cmd=parser.command_line(entity.get_attr("cmd")),
            name=parser.subs(entity, "name"),
            **parser.process_kwargs(entity),
        )

    def __init__(
        self,
        *,
        cmd: Any,
        name: Any = None,
        cwd: Any = None,
        env: dict | None = None,
        additional_env: dict | None = None,
        shell: bool = False,
        output: Any = "log",
        emulate_tty: bool = False,
        respawn: Any = False,
        respawn_delay: float | None = None,
        respawn_max_retries: int = -1,
        sigterm_timeout: Any = None,
        sigkill_timeout: Any = None,
        prefix: Any = None,
        arguments: Any = None,
        cached_output: bool = False,
        log_cmd: bool = False,
        on_exit: Any = None,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        parts = [cmd] if isinstance(cmd, str) and shell else list(cmd)
        self.cmd = [normalize_to_list_of_substitutions(x) for x in parts]
        self.cmd += [normalize_to_list_of_substitutions(x) for x in (arguments or [])]
        self.name = None if name is None else normalize_to_list_of_substitutions(name)
        self.cwd = None if cwd is None else normalize_to_list_of_substitutions(cwd)
        self.env = env
        self.additional_env = additional_env
        self.shell = shell
        override = os.environ.get("OVERRIDE_LAUNCH_PROCESS_OUTPUT")
        self.output = override or output
        self.emulate_tty = emulate_tty
        self.respawn = respawn
        self.respawn_delay = respawn_delay
        self.respawn_max_retries = respawn_max_retries
        self.sigterm_timeout = normalize_to_list_of_substitutions(
            LaunchConfiguration("sigterm_timeout", default=5)
            if sigterm_timeout is None
            else str(sigterm_timeout)
        )
        self.sigkill_timeout = normalize_to_list_of_substitutions(
            LaunchConfiguration("sigkill_timeout", default=5)
            if sigkill_timeout is None
            else str(sigkill_timeout)
        )
        self.prefix = prefix
        self.log_cmd = log_cmd
        self.on_exit = on_exit
        self.spec: ProcessSpec | None = None
        self._future: Any = None

    def _final_cmd(self, context: Any) -> list[str]:
        """Return the command line with every substitution performed."""
        cmd = [perform_substitutions(context, part) for part in self.cmd]
        prefix = self.prefix
        if prefix is None:
            prefix = context.launch_configurations.get("launch-prefix", "")
        else:
            prefix = perform_substitutions(context, normalize_to_list_of_substitutions(prefix))
        return shlex.split(prefix) + cmd

    def _final_env(self, context: Any) -> dict[str, str]:
        def resolve(items: dict) -> dict[str, str]:
            return {
                perform_substitutions(
                    context, normalize_to_list_of_substitutions(k)
                ): perform_substitutions(context, normalize_to_list_of_substitutions(v))
                for k, v in items.items()
            }

        env = resolve(self.env) if self.env is not None else dict(context.environment)
        env.update(resolve(self.additional_env or {}))
        return env

    def prepare(self, context: Any) -> ProcessSpec:
        """Resolve everything and give the process its unique name (`exe-N`)."""
        cmd = self._final_cmd(context)
        base = (
            os.path.basename(cmd[0])
            if self.name is None
            else perform_substitutions(context, self.name)
        )
        context.process_counter += 1
        output = self.output
        if not isinstance(output, dict):
            output = perform_substitutions(context, normalize_to_list_of_substitutions(output))
        emulate_tty = self.emulate_tty
        if "emulate_tty" in context.launch_configurations:
            emulate_tty = _truthy(context.launch_configurations["emulate_tty"])
        respawn = self.respawn
        if not isinstance(respawn, bool):
            respawn = _truthy(
                perform_substitutions(context, normalize_to_list_of_substitutions(respawn))
            )
        cwd = None if self.cwd is None else perform_substitutions(context, self.cwd)
        sigterm_timeout, sigkill_timeout = self._timeouts(context)
        return ProcessSpec(
            name=f"{base}-{context.process_counter}",
            cmd=cmd,
            cwd=cwd,
            env=self._final_env(context),
            output=output,
            emulate_tty=bool(emulate_tty),
            shell=self.shell,
            respawn=respawn,
            respawn_delay=self.respawn_delay,
            respawn_max_retries=self.respawn_max_retries,
            sigterm_timeout=sigterm_timeout,
            sigkill_timeout=sigkill_timeout,
        )

    def _timeouts(self, context: Any) -> tuple[str, str]:
        """Return the SIGTERM and SIGKILL timeouts: the second counts from SIGINT too."""
        sigterm = perform_substitutions(context, self.sigterm_timeout)
        sigkill = perform_substitutions(context, self.sigkill_timeout)
        return sigterm, str(float(sigterm) + float(sigkill))

    def execute(self, context: Any) -> None:
        self.spec = self.prepare(context)
        if context.is_shutdown:
            return None
        if context.runtime is None:
            context.planned_processes.append(self)
            return None
        context.register_event_handler(_SignalHandler(self, context.runtime))
        context.register_event_handler(OnShutdown(on_shutdown=self._on_shutdown))
        if self.on_exit is not None:
            context.register_event_handler(OnProcessExit(target_action=self, on_exit=self.on_exit))
        self._future = context.runtime.start_process(self, self.spec)
        return None

    def _on_shutdown(self, event: Any, context: Any) -> None:
        send_sigint = not event.due_to_sigint or context.noninteractive
        context.runtime.shutdown_process(self, send_sigint=send_sigint)

    def get_asyncio_future(self) -> Any:
        """Return the future done once the process (and its respawns) have ended."""
        return self._future


class _SignalHandler(BaseEventHandler):
    """Send the signals that shutdown asks for, in event order (as launch does)."""

    def __init__(self, action: ExecuteProcess, runtime: Any) -> None:
        super().__init__(
            matcher=lambda event: isinstance(event, SignalProcess) and event.action is action
        )
        self.runtime = runtime

    def handle(self, event: Any, context: Any) -> None:
        super().handle(event, context)
        self.runtime.signal_process(event.action, event.signal_name)
