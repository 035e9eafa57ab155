"""The environment's `python3` kernel spec: the course's kernel (notebook.kernel_launcher)."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

from ..core.files.atomic_files import atomic_write

__all__ = ["KERNEL_NAME", "LAUNCHER", "install_kernelspec", "kernelspec"]

KERNEL_NAME = "python3"
LAUNCHER = "course_lib.notebook.kernel_launcher"


def kernelspec() -> dict[str, Any]:
    """Return ipykernel's own spec, started by the course's launcher, without a debugger."""
    from ipykernel.kernelspec import get_kernel_dict, make_ipkernel_cmd

    spec = get_kernel_dict()
    # "python": Jupyter starts the kernel with its own interpreter, wherever the clone is
    spec["argv"] = make_ipkernel_cmd(mod=LAUNCHER, executable="python")
    spec["metadata"] = {**spec.get("metadata", {}), "debugger": False}
    return spec


def install_kernelspec(prefix: str | Path = sys.prefix) -> Path:
    """Write the spec over ipykernel's in `prefix` (pip writes its own at each install)."""
    target = Path(prefix) / "share" / "jupyter" / "kernels" / KERNEL_NAME / "kernel.json"
    return atomic_write(target, json.dumps(kernelspec(), indent=1) + "\n")
