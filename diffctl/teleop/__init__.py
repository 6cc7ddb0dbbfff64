"""Teleoperation: teleop_twist_keyboard, and `diffctl teleop joy` (joy_node + teleop_node in one process)."""
