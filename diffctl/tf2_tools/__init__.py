"""tf2_ros's command-line tools (`static_transform_publisher`, `tf2_echo`) as executables of package tf2_ros."""
