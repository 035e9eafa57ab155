"""The course's Python kernel: ipykernel without its visual debugger.

ipykernel imports debugpy as it starts, for JupyterLab's debugger panel: about 8 MiB in every
kernel, and a learner keeps several lessons' kernels open. Nothing in the lessons is stepped
through, so this kernel starts ipykernel with debugpy unavailable, the way ipykernel runs
where debugpy is not installed (no debugger panel). `make setup` makes it the environment's
`python3` kernel (`course_lib.tools.kernelspec`). It loads `cell_errors` as it starts.
"""

from __future__ import annotations

import sys
from pathlib import Path

CELL_ERRORS = "course_lib.notebook.cell_errors"


def main() -> None:
    """Start the kernel as ipykernel_launcher does, with `import debugpy` failing."""
    if sys.path and (sys.path[0] == "" or Path(sys.path[0]) == Path.cwd()):
        del sys.path[0]  # as ipykernel_launcher: the kernel puts the cwd back itself
    sys.modules["debugpy"] = None  # type: ignore[assignment]  # Python's "not installed"
    from ipykernel import kernelapp

    # a cell run before the lesson's first (a new or restarted kernel) says what to run
    kernelapp.launch_new_instance(extra_extensions=[CELL_ERRORS])


if __name__ == "__main__":
    main()
