"""ros2/demos' `demo_nodes_cpp` and `demo_nodes_py` nodes, for machines where those packages are not installed.

Launch tests copied from the ROS docs start `Node(package='demo_nodes_cpp', executable='talker')`. These nodes
behave as the Jazzy ones do: same node, topic and service names, QoS depths, rates, counters and log lines
(the C++ talker counts from 1 and quotes with '…', the Python one counts from 0 and quotes with "…"). They are
written on rclpy (diffctl's client, or a sourced ROS 2's) and start as `python -m diffctl.demo_nodes PKG EXE`.
A package of the user's workspace or of an install tree with the same name always wins (the workspace's
package index asks here last).
"""

from __future__ import annotations

import sys

# (package, executable) → "module:function" in this package
PROGRAMS: dict[tuple[str, str], str] = {
    ("demo_nodes_cpp", "talker"): "topics:cpp_talker",
    ("demo_nodes_cpp", "listener"): "topics:cpp_listener",
    ("demo_nodes_cpp", "add_two_ints_server"): "services:cpp_server",
    ("demo_nodes_cpp", "add_two_ints_client"): "services:cpp_client",
    ("demo_nodes_cpp", "parameter_blackboard"): "parameters:blackboard",
    ("demo_nodes_cpp", "set_and_get_parameters"): "parameters:set_and_get",
    ("demo_nodes_py", "talker"): "topics:py_talker",
    ("demo_nodes_py", "listener"): "topics:py_listener",
    ("demo_nodes_py", "talker_qos"): "topics:py_talker_qos",
    ("demo_nodes_py", "listener_qos"): "topics:py_listener_qos",
    ("demo_nodes_py", "add_two_ints_server"): "services:py_server",
    ("demo_nodes_py", "add_two_ints_client"): "services:py_client",
}

PACKAGES = tuple(sorted({pkg for pkg, _ in PROGRAMS}))


def executables(package: str) -> list[str]:
    return sorted(exe for pkg, exe in PROGRAMS if pkg == package)


def argv_for(package: str, executable: str) -> list[str] | None:
    """The command line of a demo node, or None when diffctl has no node of that name."""
    if (package, executable) not in PROGRAMS:
        return None
    return [sys.executable, "-m", "diffctl.demo_nodes", package, executable]
