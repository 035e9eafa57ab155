"""The course's Python kernel: ipykernel without its visual debugger.

ipykernel imports debugpy as it starts, for JupyterLab's debugger panel: about 8 MiB in every
kernel, and a learner keeps several lessons' kernels open. Nothing in the lessons is stepped
through, so this kernel starts ipykernel with debugpy unavailable, the way ipykernel runs
where debugpy is not installed (no debugger panel). `make setup` makes it the environment's
`python3` kernel (`course_lib.tools.kernelspec`).
"""

from __future__ import annotations

import sys
from pathlib import Path


def main() -> None:
    """Start the kernel as ipykernel_launcher does, with `import debugpy` failing."""
    if sys.path and (sys.path[0] == "" or Path(sys.path[0]) == Path.cwd()):
        del sys.path[0]  # as ipykernel_launcher: the kernel puts the cwd back itself
    sys.modules["debugpy"] = None  # type: ignore[assignment]  # Python's "not installed"
    from ipykernel import kernelapp

    kernelapp.launch_new_instance()


if __name__ == "__main__":
    main()
