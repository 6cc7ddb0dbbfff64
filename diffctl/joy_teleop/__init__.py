"""joy_teleop (teleop_tools): sensor_msgs/Joy → configured topics, service calls and action goals."""
