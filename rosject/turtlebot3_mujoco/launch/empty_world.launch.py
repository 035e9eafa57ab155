"""Start the MuJoCo TurtleBot3 Waffle Pi world, as turtlebot3_gazebo's empty_world does."""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    """Describe one process that runs the physics and all the simulated robot's nodes."""
    real_time_factor = LaunchConfiguration('real_time_factor')
    return LaunchDescription(
        [
            DeclareLaunchArgument(
                'real_time_factor',
                default_value='1.0',
                description='Simulated seconds per wall second (0: as fast as possible).',
            ),
            # No `name=`: the process holds several nodes (/mujoco, /turtlebot3_diff_drive, ...),
            # and a name remap would rename every one of them.
            Node(
                package='turtlebot3_mujoco',
                executable='simulation',
                output='screen',
                emulate_tty=True,
                arguments=['--real-time-factor', real_time_factor],
            ),
        ]
    )
