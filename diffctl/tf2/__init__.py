"""tf2 for diffctl: the transform buffer's math and tree walk (`buffer_core`, pure) and its ROS I/O
(`ros_io`: Buffer, TransformListener and the broadcasters over the rclpy-compatible client), mapped to
ROS's names by the overlay's `tf2_ros` / `tf2_py` / `tf2_geometry_msgs` modules."""
