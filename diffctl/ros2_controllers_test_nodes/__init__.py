"""ros2_controllers_test_nodes: the goal publishers ros2_control_demos' test launch files start."""
