"""How a course error looks in a notebook: the message and `Try:` line, no internals."""

from __future__ import annotations

import sys
from typing import Any

__all__ = ["show_course_error"]


def show_course_error(shell: Any, etype: type, value: BaseException, tb: Any, tb_offset=None):
    """IPython custom exception handler: print the error as the learner should read it."""
    print(f"{etype.__name__}: {value}", file=sys.stderr)
    return None
