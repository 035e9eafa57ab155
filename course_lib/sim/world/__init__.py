"""The MuJoCo world of the robot: model, physics, frames, kinematics, pacing (no ROS)."""
