"""robot_state_publisher, joint_state_publisher and ros_gz_bridge list, describe and refuse parameters as the
real packages do, seen through their parameter services from the bus.

robot_state_publisher and ros_gz_bridge are rclcpp nodes: their tables below are what their Jazzy sources
declare (robot_state_publisher 3.3 `src/robot_state_publisher.cpp`; ros_gz_bridge `src/ros_gz_bridge.cpp`,
`src/parameter_bridge.cpp`, `src/factory.hpp`; tf2_ros' broadcasters' QoS overriding options) plus what rclcpp
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
STRING, INTEGER, DOUBLE, BOOL = 4, 2, 3, 1
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
def test_rsp_jsp_and_bridge_declare_what_upstream_declares(router: str, procs: Any) -> None:
    rsp = procs.diffctl("robot-state-publisher", "--description", str(CAR))
    jsp = procs.diffctl("joint-state-publisher")
    bridge = procs.diffctl("bridge", "/clock@rosgraph_msgs/msg/Clock[gz.msgs.Clock",
                           "/cmd_vel@geometry_msgs/msg/Twist]gz.msgs.Twist")
    p = probe("param_probe")
    try:
        got = {}
        for proc, fqn in ((rsp, "/robot_state_publisher"), (jsp, "/joint_state_publisher"),
                          (bridge, "/ros_gz_bridge")):
            assert wait_for(lambda f=fqn: _fqn_of(p, f) == f, 30), (procs.stop(proc), proc.stdout.read())
            got[fqn] = parameters(p, fqn)
        assert _table(got["/robot_state_publisher"]) == RSP
        assert _table(got["/ros_gz_bridge"]) == BRIDGE
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
    for proc in (rsp, jsp, bridge):
        assert procs.stop(proc) == 0, proc.stdout.read()
