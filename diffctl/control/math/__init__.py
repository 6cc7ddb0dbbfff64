"""Pure controller math (no I/O, no bus): speed limiter, rolling mean, diff-drive odometry and kinematics."""
