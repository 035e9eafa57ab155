"""Which node processes run in a lab, and which notebook's kernel started each (a walk's log).

Read from /proc (psutil) and the lab's sessions API, never through ROS: when the graph shows a
name twice, this says whose processes they are.
"""

from __future__ import annotations

import json
import re
import urllib.request

import psutil
from lab_server import LabServer

__all__ = ["node_processes"]

NODE_EXECUTABLES = ("/param_vel", "/descriptor_vel")


def _kernels(lab: LabServer) -> dict[str, str]:
    """Return notebook paths by kernel id, as the lab's sessions API lists them."""
    request = urllib.request.Request(
        f"{lab.base_url}/api/sessions", headers={"Authorization": f"token {lab.token}"}
    )
    with urllib.request.urlopen(request, timeout=10) as answer:
        sessions = json.load(answer)
    return {s["kernel"]["id"]: s["path"].rsplit("/", 1)[-1] for s in sessions if s.get("kernel")}


def _owner(process: psutil.Process, kernels: dict[str, str]) -> str:
    """Return who started `process`: the notebook whose kernel is an ancestor, or the lab."""
    for parent in process.parents():
        found = re.search(r"kernel-([0-9a-f-]+)\.json", " ".join(parent.cmdline()))
        if found:
            return f"{kernels.get(found[1], 'a shut-down notebook')} (kernel pid {parent.pid})"
    return "the lab"


def node_processes(lab: LabServer) -> list[str]:
    """Return one line per node process of the lab's domain, wherever it runs: pid, program,
    and who started it (a notebook's kernel, the lab, or a process outside the lab's tree)."""
    try:
        kernels = _kernels(lab)
        inside = {p.pid for p in psutil.Process(lab.process.pid).children(recursive=True)}
    except (psutil.Error, OSError, ValueError) as exc:
        return [f"(could not list the lab's nodes: {exc})"]
    lines = []
    for process in psutil.process_iter():
        try:
            argv = process.cmdline()
            program = next((a for a in argv if a.endswith(NODE_EXECUTABLES)), None)
            if program is None:
                continue
            domain = process.environ().get("ROS_DOMAIN_ID")
            if process.pid not in inside and domain != str(lab.domain_id):
                continue  # another lab's, another test's
            name = program.rsplit("/", 1)[-1]
            if process.pid in inside:
                who = _owner(process, kernels)
            else:
                parent = process.parent()
                who = f"outside the lab (parent {parent.pid if parent else '?'}: " + (
                    f"{' '.join(parent.cmdline())[:80]})" if parent else "none)"
                )
            lines.append(f"{name} pid {process.pid} from {who}")
        except psutil.Error:  # gone (or a zombie) since the listing
            continue
    return sorted(lines)


_GID_BLOCK = re.compile(r"Node name: (\S+)\nNode namespace: (\S+)\n.*?\nGID: ([0-9a-f.]+)", re.S)


def hosts_of(verbose_info: str, node: str) -> list[str]:
    """Return, for each publisher of `node` in `ros2 topic info -v` text, the processes that may
    hold it: Fast DDS puts the low 16 bits of the pid in bytes 4-5 of an endpoint's GID."""
    lines = []
    for name, namespace, gid in _GID_BLOCK.findall(verbose_info):
        if namespace.rstrip("/") + "/" + name != node:
            continue
        octets = [int(part, 16) for part in gid.split(".")]
        bits = octets[4] | octets[5] << 8
        holders = []
        for process in psutil.process_iter():
            if process.pid & 0xFFFF != bits:
                continue
            try:
                holders.append(f"pid {process.pid} {' '.join(process.cmdline())[:120]}")
            except psutil.Error:
                holders.append(f"pid {process.pid} (gone)")
        lines.append(f"{node} GID {gid}: {'; '.join(holders) or 'no live process'}")
    return lines
