"""`python -m course_lib.sim`: run the MuJoCo TurtleBot3 world and its ROS 2 nodes."""

import sys

from .world_process import main

sys.exit(main())
