"""The one reader of the ament index: which resources (packages, interfaces) a prefix holds.

It reads the prefixes it is given, not os.environ: the course answers for the environment of
a session, a learner's terminal or a sourced workspace (`ros2/daemon.py` serves several at
once, from threads), while ament_index_python's readers only search the process's own
AMENT_PREFIX_PATH. The rules are ament_index_python's: the first prefix that holds a resource
wins, and subfolders and names starting with a dot are no resources. `launch/resolve.py`,
which runs with the environment it answers for, uses ament_index_python itself, so its
messages are `ros2 launch`'s word for word.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping
from pathlib import Path

__all__ = ["INDEX", "prefix_path", "resource", "resource_prefix", "resources"]

INDEX = Path("share") / "ament_index" / "resource_index"


def prefix_path(env: Mapping[str, str]) -> list[Path] | None:
    """Return the prefixes AMENT_PREFIX_PATH lists, in its order; None if it is unset."""
    raw = env.get("AMENT_PREFIX_PATH")
    return None if raw is None else [Path(p) for p in raw.split(os.pathsep) if p]


def resources(kind: str, roots: Iterable[Path]) -> dict[str, Path]:
    """Return the names of the resources of `kind`, each with the first prefix holding it."""
    found: dict[str, Path] = {}
    for root in roots:
        folder = root / INDEX / kind
        if folder.is_dir():
            for entry in sorted(folder.iterdir()):
                if not entry.name.startswith(".") and not entry.is_dir():
                    found.setdefault(entry.name, root)
    return found


def resource_prefix(kind: str, name: str, roots: Iterable[Path]) -> Path | None:
    """Return the first prefix that holds resource `name` of `kind`, or None."""
    return next((root for root in roots if (root / INDEX / kind / name).is_file()), None)


def resource(kind: str, name: str, roots: Iterable[Path]) -> str:
    """Return the content of resource `name` of `kind`; raise LookupError if none holds it."""
    root = resource_prefix(kind, name, roots)
    if root is None:
        raise LookupError(f"Could not find the resource '{name}' of type '{kind}'")
    return (root / INDEX / kind / name).read_text()
