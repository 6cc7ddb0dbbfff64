"""Teleoperation: teleop_twist_keyboard and joy + teleop_twist_joy counterparts publishing velocity commands."""
