"""rclpy.action for diffctl: the goal state machine (`goal_states`, pure), ActionServer (`server`) and
ActionClient (`client`) on rmw_zenoh's action keys: services `<action>/_action/{send_goal,cancel_goal,
get_result}`, topics `<action>/_action/{feedback,status}`; graph queries (`graph`)."""
