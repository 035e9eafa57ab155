"""`make stop` inside and outside a lab, run in a PID namespace of its own by test_make_stop.py.

`python -m course_lib stop` stops every course process of the user: on a shared machine it
would stop other sessions' processes too, so this scenario runs where it sees only its own
(`unshare --pid --mount-proc`) with a runtime folder of its own (TMPDIR). It prints one JSON
line of facts for the test to check.
"""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
TESTS = HERE.parent
sys.path[:0] = [
    str(HERE),
    str(TESTS / "harness"),
    str(TESTS / "support" / "lab"),
    str(TESTS / "browser"),
]

from jupyter_kernels import describe, pid_alive  # noqa: E402
from lab_server import LabServer  # noqa: E402
from lab_terminal import RestTerminal, lab_daemon  # noqa: E402
from suite_env import independent_env  # noqa: E402

from course_lib.core.host.signalling import LOG_ENV  # noqa: E402
from course_lib.core.paths import REPO_ROOT  # noqa: E402
from course_lib.core.waiting import wait_until  # noqa: E402
from course_lib.processes.ownership import read_process  # noqa: E402

PY = sys.executable
HANG_UP_S = 5.0  # a hung-up job's end, after the lab's: milliseconds, seconds on a busy host
# The learner's script in the terminal: a session with the tutorial node, and a child that
# ignores SIGINT and SIGTERM (only SIGKILL ends it).
LEARNER_SCRIPT = """
import sys, time
from course_lib.session.session import get_session
session = get_session()
node = session.run("parameter_tests", "param_vel")
stubborn = session.spawn(
    [sys.executable, "-c", "import signal, time; signal.signal(signal.SIGINT, signal.SIG_IGN);"
     "signal.signal(signal.SIGTERM, signal.SIG_IGN); print('up', flush=True); time.sleep(600)"],
    name="stubborn",
)
stubborn.wait_for_line("up", 10)
node.wait_for_line("Velocity parameter is", 60)  # running, as when a learner types `make stop`
print(f"node-pid={node.pid} stubborn-pid={stubborn.pid}", flush=True)
time.sleep(600)
"""


def signals_to(log: Path, pid: int) -> list[str]:
    """Return the signals the COURSE_SIGNAL_LOG file `log` says were sent to `pid` (or its
    group), in order."""
    lines = log.read_text().splitlines() if log.exists() else []
    targets = (f" to pid {pid} (", f" to group {pid} (")
    sent = [line for line in lines if any(target in line for target in targets)]
    return [line.split(" sends ", 1)[1].split()[0] for line in sent]


def children(pid: int) -> list[int]:
    """Return the live children of `pid`."""
    found = []
    for entry in os.listdir("/proc"):
        info = read_process(int(entry)) if entry.isdigit() else None
        if info is not None and info.ppid == pid:
            found.append(info.pid)
    return found


def named_child(pid: int, word: str) -> int:
    """Return the child of `pid` whose command line contains `word`."""
    for child in children(pid):
        if word in " ".join(read_process(child).argv):  # type: ignore[union-attr]
            return child
    raise AssertionError(f"no child of {pid} runs {word}:\n{describe(children(pid))}")


def printed_by_stop(output: str) -> str:
    """Return what `course_lib stop` printed in the terminal (no echo, prompt or escapes)."""
    text = re.sub(r"\x1b\[[0-9;?]*[a-zA-Z]|\r", "", output).rsplit("stop-exit=", 1)[0]
    lines = text.splitlines()
    typed = [i for i, line in enumerate(lines) if "-m course_lib stop" in line]
    return "\n".join(lines[typed[-1] + 1 if typed else 0 :])


def main() -> None:
    # A suite started under nohup hands an ignored SIGHUP down to the lab's terminals, whose
    # shells and jobs then outlive any hang-up: the lab here starts as from a login shell.
    signal.signal(signal.SIGHUP, signal.SIG_DFL)
    env = independent_env()
    folder = REPO_ROOT / "test-artifacts" / "faults" / "make-stop"
    lab = LabServer([], folder, env=env)
    (folder / "learner.py").write_text(LEARNER_SCRIPT)
    facts: dict[str, object] = {}
    pids = {"lab": lab.process.pid}
    pids["jupyterlab"] = named_child(lab.process.pid, "jupyter-lab")
    terminal = RestTerminal(lab.base_url, lab.token)
    pids["daemon"] = lab_daemon(lab.process.pid)  # the lab's first terminal starts it
    pids["shell"] = terminal.shell_pid
    # the learner's own programs, which inherit the lab's environment (and its owner tag)
    pids["editor"] = int(terminal.run("sleep 600 & echo bg-pid=$!", r"bg-pid=(\d+)")[1])
    # a program meant to outlive the lab (nohup: the terminal's hang-up spares it)
    logger = terminal.run("nohup sleep 700 >/dev/null 2>&1 & echo bg-pid=$!", r"bg-pid=(\d+)")
    pids["logger"] = int(logger[1])
    started = terminal.run(
        f"{PY} {folder / 'learner.py'} &", r"node-pid=(\d+) stubborn-pid=(\d+)", timeout=90
    )
    pids["node"], pids["stubborn"] = int(started[1]), int(started[2])
    pids["script"] = read_process(pids["node"]).ppid  # type: ignore[union-attr]

    began, before = time.monotonic(), len(terminal.output)
    signals = folder / "stop-signals.log"  # what `make stop` sent, kept with the artifacts
    signals.unlink(missing_ok=True)
    inside = terminal.run(
        f"{LOG_ENV}={signals} {PY} -m course_lib stop; echo stop-exit=$?", r"stop-exit=(\d+)"
    )
    facts["inside_seconds"] = round(time.monotonic() - began, 2)
    facts["inside_exit"] = int(inside[1])
    facts["inside_output"] = printed_by_stop(terminal.output[before:])
    facts["alive_after_inside"] = {name: pid_alive(pid) for name, pid in pids.items()}
    facts["signals_to_node"] = signals_to(signals, pids["node"])
    facts["shell_answers"] = bool(terminal.run("echo still-$((2+3))", r"still-5"))
    terminal.close()

    began = time.monotonic()
    outside = subprocess.run(
        [PY, "-m", "course_lib", "stop"], env=env, capture_output=True, text=True, check=False
    )
    facts["outside_seconds"] = round(time.monotonic() - began, 2)
    facts["outside_exit"] = outside.returncode
    facts["outside_output"] = outside.stdout + outside.stderr
    lab.process.wait(10.0)
    # The lab's end hangs up its terminals; their shells then hang up their jobs (the
    # learner's `sleep 600 &`): moments after the lab's own exit, not before it.
    ours = [pid for name, pid in pids.items() if name != "logger"]
    wait_until(lambda: not any(pid_alive(pid) for pid in ours), HANG_UP_S)
    facts["alive_after_outside"] = {name: pid_alive(pid) for name, pid in pids.items()}
    others = [int(e) for e in os.listdir("/proc") if e.isdigit() and int(e) != os.getpid()]
    left = [p for p in others if pid_alive(p) and p != pids["logger"]]
    facts["left_running"] = describe(left)
    facts["pids"] = pids
    print(json.dumps(facts), flush=True)


if __name__ == "__main__":
    main()
