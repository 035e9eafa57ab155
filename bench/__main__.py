"""`make bench`: run every bench script in turn and print one report."""

from __future__ import annotations

import os
import platform
import subprocess
import sys
import time
from datetime import datetime, timezone
from pathlib import Path

BENCH_DIR = Path(__file__).resolve().parent


def main() -> int:
    scripts = sorted(p for p in BENCH_DIR.glob("*.py") if not p.name.startswith("_"))
    failed = []
    started = time.monotonic()
    print(
        f"ROS 2 course bench, {datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC, "
        f"{os.cpu_count()} cores, Python {platform.python_version()}; "
        "goals, where a script prints one, are never asserted",
        flush=True,
    )
    for script in scripts:
        print(f"\n== {script.stem} ==", flush=True)
        module = f"bench.{script.stem}"
        t0 = time.monotonic()
        if subprocess.run([sys.executable, "-m", module], check=False).returncode != 0:
            failed.append(script.stem)
        print(f"   ({script.stem}: {time.monotonic() - t0:.0f} s)", flush=True)
    print(f"\nbench total: {time.monotonic() - started:.0f} s")
    if failed:
        print(f"\nbench scripts that failed: {', '.join(failed)}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
