"""sensor_msgs_py (common_interfaces, Jazzy): Python helpers for sensor_msgs, from diffctl.interfaces."""
