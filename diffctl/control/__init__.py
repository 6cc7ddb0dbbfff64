"""ros2_control in Python: controller manager, hardware plugins, controllers, spawner and CLI."""
