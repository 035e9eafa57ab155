"""Lesson 3's comparison of the simulation's topics with the tutorial's (pure, no ROS)."""

from __future__ import annotations

from course_lib.lessons.sim_tutorial import compare_with_tutorial

# The list of what the course's `ros2 topic list` shows in the simulation.
COURSE_TOPICS = [
    *("/camera/camera_info", "/camera/image_raw", "/clock", "/cmd_vel", "/imu"),
    *("/joint_states", "/odom", "/parameter_events", "/robot_description", "/rosout"),
    *("/scan", "/tf", "/tf_static"),
]


def test_the_one_difference_is_gazebos_performance_metrics() -> None:
    comparison = compare_with_tutorial(COURSE_TOPICS)
    assert comparison.only_tutorial == ("/performance_metrics",)
    assert comparison.only_here == ()
    text = repr(comparison)
    assert text.startswith("Topics of the tutorial's Gazebo world also here: 13 of 14\n")
    assert "Only in the tutorial: /performance_metrics\n  Gazebo's own message" in text
    assert text.endswith("Only here: nothing\n")


def test_a_missing_tf_and_an_extra_topic_are_named() -> None:
    names = [n for n in COURSE_TOPICS if n != "/tf"] + ["/velocity"]
    text = repr(compare_with_tutorial(names))
    assert "Only in the tutorial: /tf\n  not simulated here\n" in text
    assert text.endswith("Only here: /velocity\n")
