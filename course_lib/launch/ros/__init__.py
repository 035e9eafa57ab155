"""launch_ros: `Node` and its parameters."""
