"""nav2_common (Nav2, Jazzy): the launch helpers robot projects import without running Nav2 itself.

`from nav2_common.launch import RewrittenYaml, ReplaceString, HasNodeParams, ParseMultiRobotPose` — substitutions
that write an edited copy of a YAML or text file and return its path, one that asks whether a parameter file
names a node, and the parser of `robots:="name={x: …};…"` launch arguments. Its CMake helpers
(nav2_package()) are not here: diffctl builds nothing.
"""
