"""A real full disk for a test: a small tmpfs, in a mount namespace of its own or (root) here.

Mounting needs privileges: root (CI) mounts in a private mount namespace (`unshare --mount`),
or here for a test whose other processes must see the disk (a kernel); anyone else tries a user
namespace (`unshare --user --map-root-user --mount`); otherwise the test is skipped, saying why.
"""

from __future__ import annotations

import contextlib
import errno
import os
import shutil
import subprocess
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest

__all__ = ["fill_disk", "mount_namespace_prefix", "small_tmpfs"]

_CHUNKS = (1 << 20, 1 << 12, 1)  # bytes: fill fast, then to the last byte


def mount_namespace_prefix() -> list[str]:
    """Return the command prefix that runs a process in a mount namespace where it may mount a
    tmpfs, or skip saying why there is none."""
    unshare = shutil.which("unshare")
    if unshare is None:
        pytest.skip("`unshare` (util-linux) is missing: no tmpfs for a full disk")
    if os.geteuid() == 0:
        prefix = [unshare, "--mount", "--propagation", "private"]
    else:
        prefix = [unshare, "--user", "--map-root-user", "--mount"]
    with tempfile.TemporaryDirectory(prefix="tmpfs-probe-") as folder:
        probe = [*prefix, "mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", folder]
        said = subprocess.run(probe, capture_output=True, text=True, check=False)
    if said.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here ({said.stderr.strip()}): run as root, as CI")
    return prefix


@contextlib.contextmanager
def small_tmpfs(folder: Path, size: str) -> Iterator[Path]:
    """Mount a tmpfs of `size` (e.g. "2m") at `folder` in this mount namespace (root only:
    other processes see it too); unmount it after, even if the body failed."""
    if os.geteuid() != 0:
        pytest.skip("mounting a tmpfs that a kernel sees needs root (CI runs as root)")
    folder.mkdir(parents=True, exist_ok=True)
    mount = ["mount", "-t", "tmpfs", "-o", f"size={size},mode=0755", "tmpfs", str(folder)]
    said = subprocess.run(mount, capture_output=True, text=True, check=False)
    if said.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs here ({said.stderr.strip()})")
    try:
        yield folder
    finally:
        if subprocess.run(["umount", str(folder)], check=False).returncode != 0:
            subprocess.run(["umount", "--lazy", str(folder)], check=True)  # still open: later


def fill_disk(folder: Path, name: str = "filler.bin") -> Path:
    """Write a file in `folder` until its disk is full to the last byte; return the file."""
    filler = folder / name
    with filler.open("wb", buffering=0) as out:
        for size in _CHUNKS:
            block = b"\0" * size
            try:
                while out.write(block):
                    pass
            except OSError as error:
                if error.errno != errno.ENOSPC:
                    raise
    return filler
