"""The host-speed line under the CPU table measures the work it names, in a fresh interpreter.

Small loops here (the suite's line runs 5M additions once, at the end of a whole run).
"""

from __future__ import annotations

import re

from host_speed import host_speed_line, loop_cpu_s, start_ms

SMALL = 500_000


def test_the_loop_figure_grows_with_the_loop() -> None:
    # four times the additions; the least of three tries each (ci93, on 2 busy cores: a ratio
    # of 6.7 where about 4 was expected)
    small = min(loop_cpu_s(SMALL) for _ in range(3))
    large = min(loop_cpu_s(4 * SMALL) for _ in range(3))
    # a figure that ignored the loop (an interpreter's start alone) would stay near 1
    assert large / small > 2.0, (small, large)


def test_the_line_gives_both_figures() -> None:
    line = host_speed_line(SMALL)
    found = re.fullmatch(
        r"host speed: 0\.5M additions in (\d+\.\d\d) CPU-s; "
        r"a bare interpreter starts in (\d+) ms \(median of 5\)",
        line,
    )
    assert found, line
    assert float(found[1]) > 0 and int(found[2]) > 0
    assert 0 < start_ms(times=1) < 10_000
