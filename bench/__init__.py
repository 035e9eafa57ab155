"""Scripts that print the course's speed and memory figures (`make bench`).

They start processes as the suite does, with the suite's environment (tests/harness).
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "harness"))
