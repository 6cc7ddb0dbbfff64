"""joint_state_publisher (the ROS node without its GUI): default JointStates for a description's free joints."""
