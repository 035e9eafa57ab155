"""The simulation's ROS side: its nodes, messages, /tf, camera, and the bridge running them."""
