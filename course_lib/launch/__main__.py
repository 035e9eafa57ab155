"""`python -m course_lib.launch ...` is `ros2 launch ...` (used for notebook launches)."""

import sys

from .command.cli import main

sys.exit(main(sys.argv[1:]))
