"""Child processes: start them in their own group, own them, stop them; ROS domains."""
