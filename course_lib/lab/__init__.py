"""A learner's lab is one ROS 2 machine: what every notebook and terminal of a lab shares.

`make lab` runs a small service next to JupyterLab (`service.MachineService`): it owns the
simulated world and its 3D view, and keeps the register of the nodes lessons started, so a
lesson can take over a node another lesson left running. Kernels reach it through `client`;
outside a lab (nbval, a plain Python process) every process keeps its own world and nodes.
"""

from .client import MachineClient, machine_client

__all__ = ["MachineClient", "machine_client"]
