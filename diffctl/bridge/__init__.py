"""ros_gz_bridge counterpart: converts simulator-side gz.msgs topics to ROS topics and back (parameter_bridge)."""
