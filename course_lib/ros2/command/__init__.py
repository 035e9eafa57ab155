"""Run one `ros2` command line: the table of verbs, parsing, the console entry, the daemon."""
