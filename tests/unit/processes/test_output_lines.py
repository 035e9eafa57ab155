"""A child's output read in few wake-ups once it is chatty, and nothing of it lost."""

from __future__ import annotations

import io
import itertools
import logging
import os
import sys
import threading
import time
from collections.abc import Iterator

import pytest

from course_lib.processes.children import spawn
from course_lib.processes.output_lines import GATHER_S, PROMPT_S, output_lines


@pytest.fixture
def pipe() -> Iterator[tuple[io.BufferedReader, int]]:
    read_fd, write_fd = os.pipe()
    reader = os.fdopen(read_fd, "rb")
    yield reader, write_fd
    reader.close()


def _write_lines(write_fd: int, count: int, every_s: float) -> threading.Thread:
    def write() -> None:
        for number in range(count):
            os.write(write_fd, f"tick {number}\n".encode())
            time.sleep(every_s)
        os.write(write_fd, b"no newline at the end")
        os.close(write_fd)

    writer = threading.Thread(target=write, daemon=True)
    writer.start()
    return writer


def test_a_chatty_child_is_read_in_few_reads_and_nothing_is_lost(
    pipe: tuple[io.BufferedReader, int],
) -> None:
    reader, write_fd = pipe
    writer = _write_lines(write_fd, 30, 0.02)  # 50 lines a second, like a busy log
    started_long_ago = time.monotonic() - PROMPT_S
    reads = list(output_lines(reader, started_long_ago))
    writer.join()
    lines = [line for batch, _at in reads for line in batch]
    assert lines == [f"tick {n}".encode() for n in range(30)] + [b"no newline at the end"]
    # 0.6 s of lines: one read a line would be 31 reads; paused reads take them in few
    assert len(reads) <= 2 + round(0.6 / GATHER_S) * 2, [len(batch) for batch, _ in reads]


def test_a_child_just_started_is_read_line_by_line(pipe: tuple[io.BufferedReader, int]) -> None:
    """The lessons time a node's first ticks from their lines: each is read when it comes."""
    reader, write_fd = pipe
    writer = _write_lines(write_fd, 5, 0.05)
    reads = list(output_lines(reader, time.monotonic()))
    writer.join()
    assert [len(batch) for batch, _at in reads] == [1] * 6
    times = [at for _batch, at in reads]
    gaps = [later - earlier for earlier, later in itertools.pairwise(times)]
    assert min(gaps[:-1]) > 0.03, gaps  # each line's time is its own, not its batch's


def test_a_failing_reader_of_the_output_is_said_once_and_the_others_read_on(
    caplog: pytest.LogCaptureFixture,
) -> None:
    code = "import time\nfor n in range(6):\n    print(n, flush=True); time.sleep(0.05)"
    child = spawn([sys.executable, "-c", code], name="counter")
    heard: list[str] = []

    def broken(_line: object) -> None:
        raise RuntimeError("a reader's own bug")

    child.add_listener(broken)
    child.add_listener(lambda line: heard.append(line.text))
    with caplog.at_level(logging.ERROR):
        assert child.wait(10.0) == 0
    # the lines after the readers were added, in order, to the last (earlier ones may be read
    # before the readers came)
    assert heard and heard == [str(n) for n in range(6)][-len(heard) :], heard
    assert caplog.text.count("a reader of counter's output failed") == 1, caplog.text
