"""`launch_pytest` is diffctl.launch_pytest under ROS's name (see diffctl/module_alias.py)."""

from diffctl.module_alias import alias

alias(__name__, "diffctl.launch_pytest")
