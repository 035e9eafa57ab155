"""One launched process: start it (pipes or a pty), relay its output, stop it like launch."""

from __future__ import annotations

import asyncio
import contextlib
import os
import pty
import signal
import time
import traceback
from typing import Any

from ...processes.children import set_parent_death_signal
from ..api.process import ProcessSpec
from ..core.events import (
    ProcessExited,
    ProcessStarted,
    ProcessStderr,
    ProcessStdout,
    SignalProcess,
)

__all__ = ["RunningProcess", "output_destinations"]

# A SIGINT right behind the terminal's one lands while the node prints its KeyboardInterrupt
# traceback and garbles it; real launch's event queue is slow enough for that not to happen.
_SIGINT_DELAY_S = 0.05


def _die_with_launch() -> None:
    """Run in the child before exec: die when the launch process dies."""
    set_parent_death_signal(signal.SIGKILL, os.getppid())


def output_destinations(config: str | dict) -> dict[str, set[str]]:
    """Map 'screen' / 'log' / 'both' / 'own_log' / 'full' (or a dict) to per-stream targets."""
    targets: dict[str, set[str]] = {"both": set(), "stdout": set(), "stderr": set()}
    aliases = {
        "screen": {"both": {"screen"}},
        "log": {"both": {"log"}, "stderr": {"screen"}},
        "both": {"both": {"log", "screen"}},
        "own_log": {"both": {"own_log"}, "stdout": {"own_log"}, "stderr": {"own_log"}},
        "full": {
            "both": {"screen", "log", "own_log"},
            "stdout": {"own_log"},
            "stderr": {"own_log"},
        },
    }
    if isinstance(config, str):
        if config not in aliases:
            raise ValueError(
                f'{config} is not a valid standard output config i.e. "screen", "log" or "both"'
            )
        targets.update(aliases[config])
    else:
        for source, dest in config.items():
            targets[source] = {dest} if isinstance(dest, str) else set(dest)
    return targets


class RunningProcess:
    """A process of the launch, from start to exit (and respawns)."""

    def __init__(self, runtime: Any, action: Any, spec: ProcessSpec) -> None:
        self.runtime = runtime
        self.action = action
        self.spec = spec
        self.pid: int | None = None
        self.returncode: int | None = None
        self.done = False
        self._proc: asyncio.subprocess.Process | None = None
        self._buffers = {"stdout": "", "stderr": ""}
        self._targets = output_destinations(spec.output)
        self._shutdown_requested: bool | None = None  # None: no; else whether to send SIGINT
        self._timers: list[asyncio.TimerHandle] = []
        self._retries = 0
        self._closing = False
        self.finished: asyncio.Future = asyncio.get_running_loop().create_future()

    def _event_args(self) -> dict[str, Any]:
        return {
            "action": self.action,
            "name": self.spec.name,
            "cmd": self.spec.cmd,
            "cwd": self.spec.cwd,
            "env": self.spec.env,
            "pid": self.pid,
        }

    def _emit_event(self, event_class: type, **kwargs: Any) -> None:
        event = event_class(**self._event_args(), **kwargs)
        context = self.runtime.context
        if context.would_handle_event(event):
            context.emit_event_sync(event)

    def _log(self, level: str, message: str) -> None:
        self.runtime.log(self.spec.name, level, message)

    def _emit(self, stream: str, line: str) -> None:
        text = f"[{self.spec.name}] {line}"
        targets = self._targets["both"] | self._targets[stream]
        out = self.runtime.out
        if "screen" in targets:
            out.screen(text)
        if "log" in targets:
            out.file(f"{time.time():.7f} {text}")
        if "own_log" in self._targets[stream]:
            out.file(text, f"{self.spec.name}-{stream}.log")
        if "own_log" in self._targets["both"]:
            out.file(text, f"{self.spec.name}.log")
        self.runtime.on_line(self.spec.name, stream, line)

    def _on_output(self, stream: str, data: bytes) -> None:
        self.runtime.process_pending_signals()
        self._emit_event(ProcessStdout if stream == "stdout" else ProcessStderr, text=data)
        buffered = self._buffers[stream] + data.decode(errors="replace")
        *lines, rest = buffered.split("\n")
        for line in lines:
            self._emit(stream, line)
        self._buffers[stream] = rest

    def _flush(self) -> None:
        for stream in ("stdout", "stderr"):
            if self._buffers[stream]:
                self._emit(stream, self._buffers[stream])
                self._buffers[stream] = ""

    async def _pump(self, fd: int, stream: str) -> None:
        loop = asyncio.get_running_loop()
        finished = loop.create_future()
        os.set_blocking(fd, False)

        def ready() -> None:
            try:
                data = os.read(fd, 65536)
            except BlockingIOError:
                return
            except OSError:  # EIO: the pty's other side is closed
                data = b""
            if data:
                self._on_output(stream, data)
                return
            loop.remove_reader(fd)
            os.close(fd)
            if not finished.done():
                finished.set_result(None)

        loop.add_reader(fd, ready)
        await finished

    async def _spawn(self) -> tuple[asyncio.subprocess.Process, list[int]]:
        opener = pty.openpty if self.spec.emulate_tty else os.pipe
        (out_r, out_w), (err_r, err_w) = opener(), opener()
        common: dict[str, Any] = {
            "stdout": out_w,
            "stderr": err_w,
            "env": self.spec.env,
            "cwd": self.spec.cwd,
            "preexec_fn": _die_with_launch,
        }
        try:
            if self.spec.shell:
                proc = await asyncio.create_subprocess_shell(" ".join(self.spec.cmd), **common)
            else:
                proc = await asyncio.create_subprocess_exec(*self.spec.cmd, **common)
        except Exception:
            for fd in (out_r, err_r):
                os.close(fd)
            raise
        finally:
            os.close(out_w)
            os.close(err_w)
        return proc, [out_r, err_r]

    async def run(self) -> None:
        """Start the process, relay its output until it exits, respawn if asked."""
        try:
            while True:
                if not await self._run_once() or not self._should_respawn():
                    break
                self._retries += 1
                if self.spec.respawn_delay:
                    await self.runtime.sleep_unless_shutdown(self.spec.respawn_delay)
                if self.runtime.shutting_down:
                    break
        finally:
            self.done = True
            self._cancel_timers()
            if not self.finished.done():
                self.finished.set_result(self.returncode)
            self.runtime.wake()

    def _should_respawn(self) -> bool:
        retries_left = self.spec.respawn_max_retries < 0 or (
            self._retries < self.spec.respawn_max_retries
        )
        return self.spec.respawn and not self.runtime.shutting_down and retries_left

    async def _run_once(self) -> bool:
        try:
            self._proc, fds = await self._spawn()
        except Exception:
            self._log(
                "ERROR", "exception occurred while executing process:\n" + traceback.format_exc()
            )
            return False
        self.pid = self._proc.pid
        self._log("INFO", f"process started with pid [{self.pid}]")
        self._emit_event(ProcessStarted)
        if self._shutdown_requested is not None:
            self._begin_shutdown(self._shutdown_requested)
        streams = ("stdout", "stderr")
        pumps = [
            asyncio.ensure_future(self._pump(fd, s)) for fd, s in zip(fds, streams, strict=True)
        ]
        self.returncode = await self._proc.wait()
        await asyncio.wait(pumps, timeout=0.5)  # grandchildren may keep a pipe open
        for pump in pumps:
            pump.cancel()
        self.runtime.process_events()  # what the process wrote is handled before its exit
        if self.returncode == 0:
            self._log("INFO", f"process has finished cleanly [pid {self.pid}]")
        else:
            self._log(
                "ERROR",
                f"process has died [pid {self.pid}, exit code {self.returncode}, "
                f"cmd '{self.spec.cmd_text}'].",
            )
        self._flush()
        self._emit_event(ProcessExited, returncode=self.returncode)
        return True

    def shutdown(self, *, send_sigint: bool) -> None:
        """Stop like launch: SIGINT (when asked), then SIGTERM and SIGKILL on timeouts."""
        if self.done or self._shutdown_requested is not None:
            return
        self._shutdown_requested = send_sigint
        if self._proc is not None:
            self._begin_shutdown(send_sigint)

    def _begin_shutdown(self, send_sigint: bool) -> None:
        loop = asyncio.get_running_loop()
        for delay, before, after in (
            (self.spec.sigterm_timeout, "SIGINT", "SIGTERM"),
            (self.spec.sigkill_timeout, "SIGTERM", "SIGKILL"),
        ):
            self._timers.append(
                loop.call_later(float(delay), self._escalate, delay, before, after)
            )
        if send_sigint:
            self.runtime.context.emit_event_sync(
                SignalProcess(action=self.action, signal_name="SIGINT")
            )

    def _escalate(self, delay: str, before: str, after: str) -> None:
        if self._proc is None or self._proc.returncode is not None:
            return
        self.runtime.log(
            self.spec.name,
            "ERROR",
            f"process[{self.spec.name}] failed to terminate '{delay}' seconds "
            f"after receiving '{before}', escalating to '{after}'",
        )
        self.signal(after)

    def signal(self, name: str) -> None:
        """Send a signal to the process, saying so as launch does."""
        if self._proc is None or self._proc.returncode is not None:
            return
        self._log("INFO", f"sending signal '{name}' to process[{self.spec.name}]")
        delay = _SIGINT_DELAY_S if name == "SIGINT" else 0.0
        asyncio.get_running_loop().call_later(delay, self._deliver, getattr(signal, name))

    def _deliver(self, signum: int) -> None:
        if self._proc is not None and self._proc.returncode is None:
            with contextlib.suppress(ProcessLookupError):
                self._proc.send_signal(signum)

    def _cancel_timers(self) -> None:
        for timer in self._timers:
            timer.cancel()
        self._timers.clear()
