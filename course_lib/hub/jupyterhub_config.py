"""JupyterHub's configuration file for the class hub: `jupyterhub -f` this file.

`python -m course_lib hub` resolves config/hub.yaml into a plan and names it in
COURSE_HUB_PLAN; this file only hands that plan to course_lib.hub.hub_config.
"""

import os

from course_lib.hub.hub_config import configure
from course_lib.hub.plan import PLAN_ENV, read_plan

configure(c, read_plan(os.environ[PLAN_ENV]))  # type: ignore[name-defined]  # noqa: F821
