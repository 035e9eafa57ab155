"""The course's image (Dockerfile): its size, its build, `run` to lesson 1, and one learner's
cost inside it against the same learner natively.

Run: .venv/bin/python -m bench.image [--cold] [--seconds 30] [--runs 3]
`make image` is timed with its cache warm (nothing changed since the last build; an edit of any
course file makes `make setup` run again in the build, about 40 s more); `--cold` first times a
build with no cache at all (every layer; the pinned packages come from uv's cache, which
`make image` lends the build). `run` to lesson 1 answering on the host is the median of
`--runs` containers. One driving learner (lesson 7's first cells, the robot at 0.2 m/s) is
measured by `bench.idle_lab --velocity 0.2` natively and inside a container: cores and PSS of
the lab and its kernel (goal: inside within 10 % of native). Nothing here is asserted.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
import uuid
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "tests" / "support" / "system"))

from course_image import (  # noqa: E402  (the tests' helper, on the path just above)
    LEARNER_HOME,
    Container,
    engine,
    remove_leftovers,
    start_build,
)

IMAGE = "ros2-params-course:bench"
WITHIN = 0.10  # issue 60: a learner in the container costs within 10 % of native
LEARNER_COPY = f"{LEARNER_HOME}/ros2-params-course"


def build(tag: str, cold: bool) -> float:
    """Build the image with `make image` (every layer again if `cold`); return the seconds."""
    began = time.monotonic()
    if start_build(tag, no_cache=cold).wait() != 0:
        raise SystemExit("make image failed: test-artifacts/image-build.log")
    return time.monotonic() - began


def image_mib(tool: str, tag: str) -> float:
    """Return the image's size (uncompressed, as the engine stores it) in MiB."""
    size = subprocess.run(
        [tool, "image", "inspect", "--format", "{{.Size}}", tag],
        capture_output=True, text=True, check=True,
    ).stdout  # fmt: skip
    return int(size.strip()) / 2**20


def learner_cost(argv_prefix: list[str], seconds: float) -> dict[str, float]:
    """Run bench.idle_lab for one driving learner behind `argv_prefix`; return its totals."""
    argv = [*argv_prefix, "-m", "bench.idle_lab", "--velocity", "0.2", "--json"]
    argv += ["--seconds", str(seconds), "--settle", "10"]
    done = subprocess.run(argv, cwd=REPO, capture_output=True, text=True, timeout=600)
    lines = [line for line in done.stdout.splitlines() if line.startswith("{")]
    if done.returncode != 0 or not lines:
        raise SystemExit(f"{' '.join(argv)} failed:\n{done.stdout[-2000:]}{done.stderr[-2000:]}")
    return json.loads(lines[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cold", action="store_true", help="also build with no cache")
    parser.add_argument("--seconds", type=float, default=30.0, help="learner window (30)")
    parser.add_argument("--runs", type=int, default=3, help="containers started (3)")
    args = parser.parse_args()
    tool = engine()
    if tool is None:
        raise SystemExit("no container engine (docker or podman) here")
    remove_leftovers(tool)
    if args.cold:
        print(f"build, no cache:         {build(IMAGE, cold=True):6.0f} s", flush=True)
    print(f"make image, warm cache:  {build(IMAGE, cold=False):6.1f} s", flush=True)
    print(f"image size:              {image_mib(tool, IMAGE):6.0f} MiB (uncompressed)")
    volume = f"ros2-course-bench-{uuid.uuid4().hex[:8]}"
    served = []
    box = None
    try:
        for number in range(args.runs):
            box = Container(tool, IMAGE, volume, name=f"{volume}-{number}")
            box.run()
            served.append(box.lesson_one()[2])
            if number < args.runs - 1:
                box.remove()
        print(f"run to lesson 1 served:  {statistics.median(served):6.2f} s (median of "
              f"{len(served)}: {', '.join(f'{s:.2f}' for s in served)})", flush=True)  # fmt: skip
        assert box is not None
        inside = learner_cost(
            [tool, "exec", "--workdir=/opt/ros2-params-course",
             f"--env=COURSE_LEARNER_ROOT={LEARNER_COPY}", box.name, ".venv/bin/python"],
            args.seconds,
        )  # fmt: skip
    finally:
        if box is not None:
            box.remove()
        subprocess.run([tool, "volume", "rm", "-f", volume], capture_output=True)
    native = learner_cost([sys.executable], args.seconds)
    print(f"one driving learner, {args.seconds:g} s:   native   container   container/native")
    for key, unit in (("cores", "cores"), ("pss_mib", "MiB PSS")):
        ratio = inside[key] / native[key] if native[key] else float("nan")
        verdict = "met" if ratio <= 1 + WITHIN else "not met"
        print(f"  {unit:<9} {native[key]:12.3f} {inside[key]:11.3f} {ratio:12.2f}"
              f"   (goal <= {1 + WITHIN:.2f}: {verdict})")  # fmt: skip


if __name__ == "__main__":
    main()
