"""The one client node: rclpy context and executor, the graph, discovery, the daemon's socket,
and the delivery of what a one-shot publisher sends from it."""
