"""One module per `ros2` verb family: its arguments, its handler and its output."""
