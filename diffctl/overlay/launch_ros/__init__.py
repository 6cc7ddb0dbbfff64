"""`launch_ros` is diffctl.launch_ros under ROS's name (see diffctl/module_alias.py)."""

from diffctl.module_alias import alias

alias(__name__, "diffctl.launch_ros")
