"""The host-speed line under the CPU table measures the work it names, in a fresh interpreter."""

from __future__ import annotations

import re

from host_speed import LOOP_ADDITIONS, host_speed_line, loop_cpu_s, start_ms


def test_the_loop_figure_grows_with_the_loop() -> None:
    # four times the additions; the least of two tries each (ci93, on 2 busy cores: 6.7 times)
    small = min(loop_cpu_s(LOOP_ADDITIONS // 4) for _ in range(2))
    large = min(loop_cpu_s(LOOP_ADDITIONS) for _ in range(2))
    # a figure that ignored the loop (an interpreter's start alone) would stay near 1
    assert large / small > 2.0, (small, large)


def test_the_line_gives_both_figures() -> None:
    line = host_speed_line()
    found = re.fullmatch(
        r"host speed: 5M additions in (\d+\.\d\d) CPU-s; "
        r"a bare interpreter starts in (\d+) ms \(median of 5\)",
        line,
    )
    assert found, line
    assert float(found[1]) > 0 and int(found[2]) > 0
    assert 0 < start_ms(times=1) < 10_000
