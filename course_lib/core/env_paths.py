"""The one way to edit a search-path variable (PATH, AMENT_PREFIX_PATH, ...): `a:b:c` lists."""

from __future__ import annotations

import os

__all__ = ["append_once", "prepend"]


def _parts(existing: str | None) -> list[str]:
    return [p for p in (existing or "").split(os.pathsep) if p]


def prepend(value: str, existing: str | None) -> str:
    """Return `existing` with `value` first (moved there if already listed), empties dropped."""
    return os.pathsep.join([value, *(p for p in _parts(existing) if p != value)])


def append_once(value: str, existing: str | None) -> str:
    """Return `existing` with `value` last, unless it is listed already (then it stays put).

    The course's workspace is the learner's underlay: a workspace sourced after it comes
    first in the caller's paths and must keep winning, as in a sourced shell.
    """
    parts = _parts(existing)
    return os.pathsep.join(parts if value in parts else [*parts, value])
