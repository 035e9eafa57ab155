"""Write the course's way into a real full disk, then a read-only one; print what happened.

Run in a mount namespace of its own (small_disk.mount_namespace_prefix) as
`python full_disk_writes.py FOLDER`: it mounts a small tmpfs at FOLDER, works there, and
prints one JSON object of facts for the test to check (the namespace's mount goes with it).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

from small_disk import fill_disk

from course_lib.core.errors import CourseError
from course_lib.core.files.atomic_files import atomic_write

OLD = "param_vel_node:\n  ros__parameters:\n    velocity: 0.0\n"
NEW = OLD.replace("0.0", "0.3") + "".join(f"# line {n}\n" for n in range(8000))  # ~100 KiB
TARGET = Path("my_files/param_vel_node.yaml")


def attempt(write: Callable[[], object]) -> dict[str, Any]:
    """Return what the write raised (its type, words, errno, filename), or that it did not."""
    try:
        write()
    except OSError as error:
        return {
            "type": type(error).__name__,
            "said": str(error),
            "errno": error.errno,
            "filename": error.filename,
            "course_error": isinstance(error, CourseError),
        }
    return {"type": None}


def listing() -> list[str]:
    return sorted(os.listdir(TARGET.parent))


def main(folder: str) -> None:
    subprocess.run(["mount", "-t", "tmpfs", "-o", "size=256k", "tmpfs", folder], check=True)
    os.chdir(folder)
    atomic_write(TARGET, OLD)
    filler = fill_disk(Path("."))
    facts: dict[str, Any] = {"full": attempt(lambda: atomic_write(TARGET, NEW))}
    facts["full_kept"] = TARGET.read_text(encoding="utf-8")
    facts["full_listing"] = listing()
    facts["full_new_file"] = attempt(lambda: atomic_write("my_files/replays/lesson07.html", NEW))
    filler.unlink()
    facts["freed"] = attempt(lambda: atomic_write(TARGET, NEW))
    facts["freed_text"] = TARGET.read_text(encoding="utf-8")
    facts["freed_listing"] = listing()
    subprocess.run(["mount", "-o", "remount,ro", folder], check=True)
    facts["read_only_folder"] = attempt(lambda: atomic_write("my_files/new/x.yaml", OLD))
    facts["read_only_file"] = attempt(lambda: atomic_write(TARGET, OLD))
    facts["read_only_kept"] = TARGET.read_text(encoding="utf-8")
    print(json.dumps(facts))


if __name__ == "__main__":
    main(sys.argv[1])
