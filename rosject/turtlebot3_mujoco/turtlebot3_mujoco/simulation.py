"""Run the course's MuJoCo TurtleBot3 world (course_lib.sim) as a ROS 2 executable."""

import sys


def main(args=None):
    """Start the world; options as `python -m course_lib.sim --help`, then --ros-args."""
    from course_lib.sim.world_process import main as run_world

    argv = [sys.argv[0], *(sys.argv[1:] if args is None else args)]
    return run_world(argv)


if __name__ == '__main__':
    sys.exit(main())
