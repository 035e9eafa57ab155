"""Start the greeting node under another name, with my_parameter set to 'earth'."""
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    greeter = Node(
        package='python_parameters',
        executable='minimal_param_node',
        name='custom_minimal_param_node',
        parameters=[{'my_parameter': 'earth'}],
        output='screen',
        emulate_tty=True,
    )
    return LaunchDescription([greeter])
