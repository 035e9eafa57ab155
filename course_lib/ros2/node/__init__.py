"""The one client node: rclpy context and executor, the graph, discovery, the daemon's socket."""
