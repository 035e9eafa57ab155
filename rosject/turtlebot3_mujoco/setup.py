from glob import glob
import os

from setuptools import find_packages, setup

package_name = 'turtlebot3_mujoco'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        (os.path.join('share', package_name, 'launch'), glob('launch/*.launch.*')),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Course maintainers',
    maintainer_email='course@example.org',
    description='The MuJoCo TurtleBot3 Waffle Pi world of the course.',
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'console_scripts': [
            'simulation = turtlebot3_mujoco.simulation:main',
        ],
    },
)
