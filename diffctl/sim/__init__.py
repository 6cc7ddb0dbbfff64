"""The PyBullet simulator: Gazebo's counterpart for SDF worlds, sensors, system plugins and ros2_control."""
