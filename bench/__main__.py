"""`make bench`: run every bench script in turn and print one report."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

BENCH_DIR = Path(__file__).resolve().parent


def main() -> int:
    scripts = sorted(p for p in BENCH_DIR.glob("*.py") if not p.name.startswith("_"))
    failed = []
    for script in scripts:
        print(f"\n== {script.stem} ==", flush=True)
        module = f"bench.{script.stem}"
        if subprocess.run([sys.executable, "-m", module], check=False).returncode != 0:
            failed.append(script.stem)
    if failed:
        print(f"\nbench scripts that failed: {', '.join(failed)}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
