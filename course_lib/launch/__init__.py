"""`ros2 launch` for the course: real ROS 2 launch files (Python, XML, YAML), run unchanged.

The `launch`/`launch_ros` modules that launch files import exist only inside the process
that evaluates them (see `shim`). `launch(...)` starts a launch from a notebook (lesson 10);
`dry_run(...)` shows each node's parameters and where they come from.

Layout (modules depend downward, toward the core; a unit test checks for import cycles):
- core: `substitution` (base, text, normalize), `event` (event and handler bases),
  `entity` (entities, `Action`, `Condition`), `events` (the event family), `context`.
- families: `substitutions`, `conditions`, `event_handlers`, `launch_argument`, `loading`
  (launch files; the XML/YAML front end registers itself there), `description`,
  `logic_substitutions`, `actions`, `event_actions`, `process`, `parameters`, `node` (launch_ros),
  `frontend_substitutions` and `frontend` (XML/YAML).
- running: `running` (one process), `runtime` (the event loop), `screen` (output).
- doors: `shim` (the `launch`/`launch_ros` modules launch files import; `real_names`),
  `resolve` (package and arguments), `cli`, `describe`, `dry_run` (`declared`), `handle`.
"""

from .command.dry_run import DryRunReport, dry_run
from .command.handle import LaunchHandle, launch

__all__ = ["DryRunReport", "LaunchHandle", "dry_run", "launch"]
