"""`python -m course_lib.book`: build the book (`make book`)."""

import sys

from .build import main

sys.exit(main())
