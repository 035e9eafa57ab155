"""A child's output, line by line, in few wake-ups when the child talks all the time.

The tutorial's node logs a line every 0.1 s. Read a line at a time, its owner's reader thread
woke ten times a second for as long as the node ran (0.001 cores of an idle lab). Past a
child's first PROMPT_S, a read that came soon after the one before is followed by a pause of
GATHER_S, and the lines printed meanwhile come in the next read, together. A child's first
lines (its start, its first ticks, whose times the lessons measure) are read as they come,
and so are the lines of a child that prints now and then.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from typing import IO

__all__ = ["GATHER_S", "PROMPT_S", "output_lines"]

PROMPT_S = 5.0  # a child's first seconds: every line is read the moment it comes
GATHER_S = 0.3  # then lines that follow each other this closely are read together
_CHUNK = 65536  # one read at most; a full one is followed at once (no child is slowed)


def output_lines(pipe: IO[bytes], started: float) -> Iterator[tuple[list[bytes], float]]:
    """Yield the lines of each read of `pipe` (without their "\\n") with the wall time of
    the read, to the pipe's end; `started` is when the child started (time.monotonic())."""
    pending = b""
    last_read = float("-inf")
    while chunk := pipe.read1(_CHUNK):  # type: ignore[attr-defined]
        now = time.monotonic()
        *lines, pending = (pending + chunk).split(b"\n")
        if lines:
            yield lines, time.time()
        chatty = now - last_read < 2 * GATHER_S and now - started >= PROMPT_S
        last_read = now
        if chatty and len(chunk) < _CHUNK:
            time.sleep(GATHER_S)
    if pending:
        yield [pending], time.time()
