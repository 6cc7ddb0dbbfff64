"""key_teleop (teleop_tools): arrow keys held in a full-screen terminal → velocity commands on `key_vel`."""
