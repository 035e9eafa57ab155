"""Environment for every test and notebook: the runner sets it, never the cells (so checked
outputs never depend on the machine)."""

import os

from course_lib.tools.testing import TEST_ENV

os.environ.update(TEST_ENV)
