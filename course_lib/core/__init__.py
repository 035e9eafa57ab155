"""The bottom layer: small jobs every other part shares; imports neither rclpy nor mujoco."""
