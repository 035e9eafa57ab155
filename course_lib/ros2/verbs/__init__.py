"""One module per `ros2` verb family: its arguments, its handler (registered beside it with
`@verb`, course_lib/ros2/verbkit/registry.py) and its output."""
