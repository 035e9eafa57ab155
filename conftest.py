"""Environment for every test and notebook: the runner sets it, never the cells (STYLE.md)."""

import os

from course_lib.testing import TEST_ENV

os.environ.update(TEST_ENV)
