"""What a killed `make lab` leaves, and cleaning it up when the next one starts.

A lab stopped with Ctrl-C removes its markers and folders itself. One that was killed
(SIGKILL, a crash, a closed machine) cannot: the next lab finds its files in the runtime
folder, stops whatever of it still runs, removes the files, and says so in one sentence.
"""

from __future__ import annotations

import shutil
from pathlib import Path

from ..core.paths import REPO_ROOT, runtime_dir
from ..processes.orphans import descended_from, reap_orphans
from ..processes.ownership import is_course_lab, lab_markers

__all__ = ["clean_up_killed_labs", "ran_from_this_clone", "workspaces_dir"]


def workspaces_dir(pid: int) -> Path:
    """Return the JupyterLab workspaces folder of lab `pid` (fresh tabs at every start)."""
    return runtime_dir() / f"workspaces-{pid}"


def _killed_labs() -> dict[int, list[Path]]:
    found = {pid: files for pid, files in lab_markers().items() if not is_course_lab(pid)}
    for folder in runtime_dir().glob("workspaces-*"):
        pid = folder.name.removeprefix("workspaces-")
        if pid.isdigit() and not is_course_lab(int(pid)):
            found.setdefault(int(pid), []).append(folder)
    return found


def ran_from_this_clone(files: list[Path]) -> bool:
    """Return True if a lab's files name this clone as the one it ran from."""
    for path in files:
        if path.name.endswith(".clone"):
            try:
                return path.read_text().strip() == str(REPO_ROOT)
            except OSError:
                return False
    return False


def clean_up_killed_labs() -> str | None:
    """Stop and remove what killed labs left; return one sentence saying so, or None."""
    killed = _killed_labs()
    if not killed:
        return None
    ours = sorted(pid for pid, files in killed.items() if ran_from_this_clone(files))
    for files in killed.values():
        for path in files:
            if path.is_dir() and not path.is_symlink():
                shutil.rmtree(path, ignore_errors=True)
            else:
                path.unlink(missing_ok=True)
    reaped = reap_orphans()  # every leftover of this user's; the sentence counts the labs'
    if not ours:  # another clone's lab (the runtime folder is per user): not this one's news
        return None
    left = descended_from(set(ours), reaped)
    killed = {pid: killed[pid] for pid in ours}
    labs = ", ".join(str(pid) for pid in sorted(killed))
    which = f"The previous lab (pid {labs})" if len(killed) == 1 else f"Earlier labs (pids {labs})"
    what = (
        f"the {len(left)} process(es) left running are stopped"
        if left
        else "nothing of it was running any more"
    )
    return (
        f"{which} ended without stopping cleanly (killed or crashed): {what}, "
        "and its files are removed."
    )
