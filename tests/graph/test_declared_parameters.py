"""robot_state_publisher, joint_state_publisher, ros_gz_bridge and foxglove_bridge list, describe and refuse
parameters as the real packages do, seen through their parameter services from the bus.

robot_state_publisher and ros_gz_bridge are rclcpp nodes: their tables below are what their Jazzy sources
declare (robot_state_publisher 3.3 `src/robot_state_publisher.cpp`; ros_gz_bridge `src/ros_gz_bridge.cpp`,
`src/parameter_bridge.cpp`, `src/factory.hpp`; tf2_ros' broadcasters' QoS overriding options; foxglove_bridge
0.8 `ros2_foxglove_bridge/src/param_utils.cpp`, which hands client_topic_whitelist and asset_uri_allowlist
param_whitelist's descriptor) plus what rclcpp
itself declares on every node (`node.cpp`, `time_source.cpp`, `node_type_descriptions.cpp`,
`detail/qos_parameters.hpp`). joint_state_publisher is an rclpy node: its declarations are run on the real
rclpy (the oracle venv) and the descriptors it ends up with are compared whole.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from tests.oracle import jazzy_venv
from tests.probe import call, parameters, probe
from tests.waiting import wait_for

REPO = Path(__file__).resolve().parents[2]
CAR = REPO / "description" / "my_diff_car.sdf"
STRING, INTEGER, DOUBLE, BOOL, STRING_ARRAY = 4, 2, 3, 1, 9
_POLICY_TYPE = {"deadline": INTEGER, "depth": INTEGER, "durability": STRING, "history": STRING,
                "liveliness": STRING, "reliability": STRING}


def qos_overrides(kind: str, topic: str, *policies: str) -> dict[str, tuple[int, str, bool]]:
    return {f"qos_overrides.{topic}.{kind}.{p}": (_POLICY_TYPE[p], f"qos policy {{{p}}} for {kind} {{{topic}}}", True)
            for p in policies}


RCLCPP_NODE = {
    "use_sim_time": (BOOL, "", False),
    "start_type_description_service": (BOOL, "Start the ~/get_type_description service for this node.", True),
    **qos_overrides("publisher", "/parameter_events", "depth", "durability", "history", "reliability"),
}
RSP = {
    **RCLCPP_NODE,
    "robot_description": (STRING, "", False), "publish_frequency": (DOUBLE, "", False),
    "frame_prefix": (STRING, "", False), "ignore_timestamp": (BOOL, "", False),
    **qos_overrides("subscription", "/joint_states", "depth", "history", "reliability"),
    **qos_overrides("publisher", "/tf", "depth", "durability", "history", "reliability"),
    **qos_overrides("publisher", "/tf_static", "depth", "history", "reliability"),
}
BRIDGE = {
    **RCLCPP_NODE,
    "subscription_heartbeat": (INTEGER, "", False), "config_file": (STRING, "", False),
    "expand_gz_topic_names": (BOOL, "", False), "override_timestamps_with_wall_time": (BOOL, "", False),
    "lazy": (BOOL, "", False),
    **qos_overrides("publisher", "/clock", "deadline", "depth", "durability", "history", "liveliness", "reliability"),
    **qos_overrides("subscription", "/cmd_vel", "depth", "history", "reliability"),
}
_WHITELIST = "List of regular expressions (ECMAScript) of whitelisted {} names."
FOXGLOVE = {
    **RCLCPP_NODE,
    "port": (INTEGER, "The TCP port to bind the WebSocket server to", True),
    "address": (STRING, "The host address to bind the WebSocket server to", True),
    "send_buffer_limit": (INTEGER, "Connection send buffer limit in bytes. Messages will be dropped when a "
                          "connection's send buffer reaches this limit to avoid a queue of outdated messages "
                          "building up.", True),
    "tls": (BOOL, "Use Transport Layer Security for encrypted communication", True),
    "certfile": (STRING, "Path to the certificate to use for TLS", True),
    "keyfile": (STRING, "Path to the private key to use for TLS", True),
    "min_qos_depth": (INTEGER, "Minimum depth used for the QoS profile of subscriptions.", True),
    "max_qos_depth": (INTEGER, "Maximum depth used for the QoS profile of subscriptions.", True),
    "best_effort_qos_topic_whitelist": (
        STRING_ARRAY, "List of regular expressions (ECMAScript) for topics that should be forced to use "
        "'best_effort' QoS. Unmatched topics will use 'reliable' QoS if ALL publishers are 'reliable', "
        "'best_effort' if any publishers are 'best_effort'.", True),
    "topic_whitelist": (STRING_ARRAY, _WHITELIST.format("topic"), True),
    "service_whitelist": (STRING_ARRAY, _WHITELIST.format("service"), True),
    "param_whitelist": (STRING_ARRAY, _WHITELIST.format("parameter"), True),
    "client_topic_whitelist": (STRING_ARRAY, _WHITELIST.format("parameter"), True),
    "asset_uri_allowlist": (STRING_ARRAY, _WHITELIST.format("parameter"), True),
    "use_compression": (BOOL, "Use websocket compression (permessage-deflate). Suited for connections with "
                        "smaller bandwith, at the cost of additional CPU load.", True),
    "capabilities": (STRING_ARRAY, "Server capabilities", True),
    "include_hidden": (BOOL, "Include hidden topics and services", True),
    "disable_load_message": (BOOL, "Do not publish as loaned message when publishing a client message", True),
    "ignore_unresponsive_param_nodes": (BOOL, "Avoid requesting parameters from previously unresponsive nodes",
                                        True),
}
# joint_state_publisher's own declarations (joint_state_publisher.py, ros2 branch): name, default, the type its
# descriptor names; every override is declared first (automatically_declare_parameters_from_overrides).
JSP_ORACLE = """
import json, rclpy
from rclpy.exceptions import ParameterAlreadyDeclaredException
from rcl_interfaces.msg import ParameterDescriptor, ParameterType as T
rclpy.init()
node = rclpy.create_node("joint_state_publisher", automatically_declare_parameters_from_overrides=True)
for name, default, kind in [("publish_default_efforts", False, T.PARAMETER_BOOL),
        ("publish_default_positions", True, T.PARAMETER_BOOL), ("publish_default_velocities", False, T.PARAMETER_BOOL),
        ("rate", 10, T.PARAMETER_INTEGER), ("source_list", [], T.PARAMETER_STRING_ARRAY),
        ("use_mimic_tags", True, T.PARAMETER_BOOL), ("use_smallest_joint_limits", True, T.PARAMETER_BOOL),
        ("delta", 0.0, T.PARAMETER_DOUBLE)]:
    try:
        node.declare_parameter(name, default, ParameterDescriptor(type=kind))
    except ParameterAlreadyDeclaredException:
        pass
names = node.list_parameters([], 0).names
print(json.dumps({d.name: [d.type, d.description, d.read_only, d.dynamic_typing, d.additional_constraints]
                  for d in node.describe_parameters(names)}))
node.destroy_node()
rclpy.shutdown()
"""


def _table(described: dict[str, Any]) -> dict[str, tuple[int, str, bool]]:
    return {n: (int(d.type), str(d.description), bool(d.read_only)) for n, d in described.items()}


def _fqn_of(p: Any, prefix: str) -> str:
    return next((n for n in p.graph.nodes() if n.startswith(prefix)), "")


@pytest.mark.slow
def test_rsp_jsp_bridges_declare_what_upstream_declares(router: str, procs: Any) -> None:
    rsp = procs.diffctl("robot-state-publisher", "--description", str(CAR))
    foxglove = procs.diffctl("foxglove-bridge", "--port", "0")
    jsp = procs.diffctl("joint-state-publisher")
    bridge = procs.diffctl("bridge", "/clock@rosgraph_msgs/msg/Clock[gz.msgs.Clock",
                           "/cmd_vel@geometry_msgs/msg/Twist]gz.msgs.Twist")
    p = probe("param_probe")
    try:
        got = {}
        for proc, fqn in ((rsp, "/robot_state_publisher"), (jsp, "/joint_state_publisher"),
                          (bridge, "/ros_gz_bridge"), (foxglove, "/foxglove_bridge")):
            assert wait_for(lambda f=fqn: _fqn_of(p, f) == f, 30), (procs.stop(proc), proc.stdout.read())
            got[fqn] = parameters(p, fqn)
        assert _table(got["/robot_state_publisher"]) == RSP
        assert _table(got["/ros_gz_bridge"]) == BRIDGE
        assert _table(got["/foxglove_bridge"]) == FOXGLOVE
        ranges = {n: [(r.from_value, r.to_value, r.step) for r in d.integer_range]
                  for n, d in got["/foxglove_bridge"].items() if d.integer_range}
        assert ranges == {"port": [(0, 65535, 1)], "send_buffer_limit": [(0, 2**63 - 1, 0)],
                          "min_qos_depth": [(0, 2**31 - 1, 1)], "max_qos_depth": [(0, 2**31 - 1, 1)]}
        assert got["/foxglove_bridge"]["port"].additional_constraints == \
            "Must be a valid TCP port number, or 0 to use a random port"
        oracle = json.loads(jazzy_venv.run_python(JSP_ORACLE).stdout.strip().splitlines()[-1])
        ours = {n: [int(d.type), str(d.description), bool(d.read_only), bool(d.dynamic_typing),
                    str(d.additional_constraints)] for n, d in got["/joint_state_publisher"].items()}
        assert ours == oracle

        # Values as upstream's defaults and QoS profiles give them.
        values = call(p, "/robot_state_publisher/get_parameters", "rcl_interfaces/srv/GetParameters",
                      {"names": ["publish_frequency", "qos_overrides./tf.publisher.depth",
                                 "qos_overrides./tf_static.publisher.depth",
                                 "qos_overrides./joint_states.subscription.reliability"]}).values
        assert (values[0].double_value, values[1].integer_value, values[2].integer_value, values[3].string_value) \
            == (20.0, 100, 1, "best_effort")

        # Sets: upstream's own check, rclcpp's type and read-only refusals, and one that passes.
        def set_one(name: str, value: dict[str, Any]) -> Any:
            return call(p, "/robot_state_publisher/set_parameters", "rcl_interfaces/srv/SetParameters",
                        {"parameters": [{"name": name, "value": value}]}).results[0]

        r = set_one("publish_frequency", {"type": DOUBLE, "double_value": 2000.0})
        assert (r.successful, r.reason) == (False, "publish_frequency must be between 0.0 and 1000.0")
        r = set_one("publish_frequency", {"type": STRING, "string_value": "fast"})
        assert (r.successful, r.reason) == (False, "Wrong parameter type, parameter {publish_frequency} is of type "
                                                   "{double}, setting it to {string} is not allowed.")
        r = set_one("qos_overrides./tf.publisher.depth", {"type": INTEGER, "integer_value": 5})
        assert (r.successful, r.reason) == (False, "parameter 'qos_overrides./tf.publisher.depth' cannot be set "
                                                   "because it is read-only")
        assert set_one("publish_frequency", {"type": DOUBLE, "double_value": 50.0}).successful
    finally:
        p.close()
    for proc in (rsp, jsp, bridge, foxglove):
        assert procs.stop(proc) == 0, proc.stdout.read()
