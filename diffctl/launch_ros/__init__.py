"""launch_ros (ROS 2 Jazzy, 0.26) on diffctl's launch core, module for module: ROS nodes and their
parameters, namespaces and remappings, composable nodes, lifecycle nodes, and the frontend tags for them.

Importing it registers its frontend tags (`node`, `node_container`, `load_composable_node`,
`push_ros_namespace`, `set_parameter`, …) and substitutions (`find-pkg-share`, `exec-in-pkg`, `param`, …);
launch's Parser imports it through the `launch.frontend.launch_extension` entry point, as ROS's.
"""

from . import actions, descriptions, event_handlers, events, ros_adapters, substitutions

__all__ = ["actions", "descriptions", "event_handlers", "events", "ros_adapters", "substitutions"]
