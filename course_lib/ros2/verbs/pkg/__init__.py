"""`ros2 pkg` and `ros2 run`: packages, their executables, new packages."""
