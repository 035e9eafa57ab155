from setuptools import find_packages, setup

package_name = 'turtlesim'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Course maintainers',
    maintainer_email='course@example.org',
    description='ROS 2 Jazzy turtlesim, as rclpy nodes.',
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'console_scripts': [
            'turtlesim_node = turtlesim.turtlesim_node:main',
            'turtle_teleop_key = turtlesim.turtle_teleop_key:main',
        ],
    },
)
