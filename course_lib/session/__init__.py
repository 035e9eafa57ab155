"""The kernel's session: one ROS domain, one rclpy client node, and its children."""
