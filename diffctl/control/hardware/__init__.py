"""Hardware plugins of the standalone manager: mock_components/GenericSystem (gz_ros2_control/GazeboSimSystem
lives in the simulator, diffctl/sim/plugins/gazebo_sim_system.py)."""
