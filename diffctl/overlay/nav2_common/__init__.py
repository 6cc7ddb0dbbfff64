"""`nav2_common` is diffctl.nav2_common under ROS's name (see diffctl/module_alias.py)."""

from diffctl.module_alias import alias

alias(__name__, "diffctl.nav2_common")
