"""joy_linux: joy_linux_node, a Linux joystick device (/dev/input/jsX) as sensor_msgs/Joy."""
