"""Environment for every test and notebook: the runner sets it, never the cells (so checked
outputs never depend on the machine)."""

import os

from course_lib.tools.notebook_outputs import OUTPUT_ENV

os.environ.update(OUTPUT_ENV)
