"""controller_manager's Python package (ros2_control, Jazzy) as launch files import it: `launch_utils`, the
spawner launch descriptions. The manager itself and its spawner are diffctl/control; the package's service
helpers (controller_manager_services) are not here.
"""
