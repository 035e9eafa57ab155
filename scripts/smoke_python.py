"""Smoke test of the interpreter running it: rclpy, one node, MuJoCo (scripts/smoke_python.sh)."""

import sys

from course_lib.config.simulation import load_simulation_settings
from course_lib.session.session import Session
from course_lib.sim.world.physics import Simulation


def main() -> int:
    session = Session()  # its own leased ROS domain, one client node spinning
    try:
        name = session.node.get_fully_qualified_name()
        print(f"rclpy node {name} in domain {session.domain_id}", flush=True)
    finally:
        session.close()
    sim = Simulation(load_simulation_settings())
    sim.command(0.2, 0.0)
    sim.step(500)
    print(f"MuJoCo: {sim.time:.2f} s simulated, robot at x = {sim.data.qpos[0]:.3f} m")
    if sim.time <= 0:
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
