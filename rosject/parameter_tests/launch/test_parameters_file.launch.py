import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    default_file = os.path.join(
        get_package_share_directory('parameter_tests'), 'config', 'param_vel_node.yaml'
    )
    return LaunchDescription(
        [
            DeclareLaunchArgument('params_file', default_value=default_file),
            Node(
                package='parameter_tests',
                executable='param_vel',
                name='param_vel_node',
                output='screen',
                parameters=[LaunchConfiguration('params_file')],
            ),
        ]
    )
