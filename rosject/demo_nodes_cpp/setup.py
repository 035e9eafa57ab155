from setuptools import find_packages, setup

package_name = 'demo_nodes_cpp'

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
    description='The parameter_blackboard of demo_nodes_cpp, as an rclpy node.',
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'console_scripts': [
            'parameter_blackboard = demo_nodes_cpp.parameter_blackboard:main',
        ],
    },
)
