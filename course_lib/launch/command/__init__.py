"""`ros2 launch` and its doors: the console command, dry runs, notebook launches."""
