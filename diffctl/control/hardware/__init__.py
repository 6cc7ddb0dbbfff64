"""Hardware plugins: mock_components/GenericSystem and gz_ros2_control/GazeboSimSystem."""
