"""joy: a joystick's axes and buttons as sensor_msgs/Joy (joy_node), read from the Linux joystick API."""
