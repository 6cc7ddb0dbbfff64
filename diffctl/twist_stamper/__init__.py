"""twist_stamper: geometry_msgs/Twist ↔ TwistStamped on cmd_vel_in → cmd_vel_out."""
