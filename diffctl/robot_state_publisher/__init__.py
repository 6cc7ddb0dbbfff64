"""robot_state_publisher: /robot_description, /tf_static for fixed joints and /tf from /joint_states."""
