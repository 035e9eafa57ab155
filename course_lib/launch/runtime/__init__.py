"""Run a launch description: the event loop, its processes, its output."""
