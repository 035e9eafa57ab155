"""The `ros2` verbs as Python functions returning structured results (what lessons call)."""
