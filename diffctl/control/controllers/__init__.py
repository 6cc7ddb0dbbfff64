"""ros2_controllers in Python: diff_drive_controller, joint_state_broadcaster, forward command controllers."""
