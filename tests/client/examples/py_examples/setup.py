from glob import glob

from setuptools import find_packages, setup

package_name = 'py_examples'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        ('share/' + package_name + '/launch', glob('launch/*.launch.py')),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='user',
    maintainer_email='user@example.com',
    description='Example nodes',
    license='Apache-2.0',
    entry_points={
        'console_scripts': [
            'fibonacci_server = py_examples.fibonacci_server:main',
            'fibonacci_client = py_examples.fibonacci_client:main',
            'lifecycle_talker = py_examples.lifecycle_talker:main',
            'lifecycle_manager = py_examples.lifecycle_manager:main',
            'tf2_broadcaster = py_examples.tf2_broadcaster:main',
            'tf2_listener = py_examples.tf2_listener:main',
            'avoider = py_examples.avoider:main',
        ],
    },
)
