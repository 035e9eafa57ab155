"""`ros2 launch` for the course: real ROS 2 launch files (Python, XML, YAML), run unchanged.

The `launch`/`launch_ros` modules that launch files import exist only inside the process
that evaluates them (see `shim`). `launch(...)` starts a launch from a notebook (lesson 10);
`dry_run(...)` shows each node's parameters and where they come from.

Layout (folders depend downward; the import-linter contract in pyproject.toml checks it):
- `core/`: entities, `Action`, `Condition`, events and handler bases, the context, launch
  descriptions, `loading` (launch files; the XML/YAML front end registers itself there),
  `real_names` (what the real modules export).
- `api/`: `actions`, `conditions`, `process` (`ExecuteProcess`), `substitutions`,
  `logic_substitutions`, `event_actions`, `substitution_syntax` (the `$(...)` language),
  `exposure` (`@expose_action`/`@expose_substitution`: where launch files find a class).
- `ros/`: launch_ros's `Node`, its `parameters`, `declared` (what a node declares).
- `frontend/`: XML and YAML launch files (`reader`).
- `runtime/`: `process_runner` (one process), `service` (the event loop), `screen` (output),
  `shim` (the `launch`/`launch_ros` modules launch files import).
- `command/`: `resolve` (package and arguments), `cli`, `describe`, `dry_run`, `handle`.
"""

from .command.dry_run import DryRunReport, dry_run
from .command.handle import LaunchHandle, launch

__all__ = ["DryRunReport", "LaunchHandle", "dry_run", "launch"]
