"""Entry point of `python -m course_lib`."""

import sys

from .tools.course_cli import main

sys.exit(main())
