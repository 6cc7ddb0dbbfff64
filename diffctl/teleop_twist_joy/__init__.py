"""teleop_twist_joy: teleop_node, sensor_msgs/Joy on `joy` → Twist or TwistStamped on `cmd_vel`."""
