"""Gazebo system plugins the simulator provides (DiffDrive, JointStatePublisher, gz_ros2_control)."""
