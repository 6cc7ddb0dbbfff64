"""`controller_manager` is diffctl.controller_manager under ROS's name (see diffctl/module_alias.py)."""

from diffctl.module_alias import alias

alias(__name__, "diffctl.controller_manager")
