"""The bottom layer: errors, paths and the runtime folder, YAML, signals, the ament index.

Imports neither rclpy nor mujoco, and nothing else of course_lib."""
