"""`launch_testing` is diffctl.launch_testing under ROS's name (see diffctl/module_alias.py)."""

from diffctl.module_alias import alias

alias(__name__, "diffctl.launch_testing")
