from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription(
        [
            Node(
                package='parameter_descriptors',
                executable='descriptor_vel',
                name='descriptor_vel_node',
                output='screen',
                parameters=[{'use_sim_time': True}],
            )
        ]
    )
