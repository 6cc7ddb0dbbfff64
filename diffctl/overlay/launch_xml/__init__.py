"""`launch_xml` is diffctl.launch_xml under ROS's name (see diffctl/module_alias.py)."""

from diffctl.module_alias import alias

alias(__name__, 'diffctl.launch_xml')
