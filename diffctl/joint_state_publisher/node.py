"""The joint_state_publisher node: its parameters as ROS 2's (Python) joint_state_publisher declares them, then
three callbacks: /robot_description (latched) or a file configures it, the source_list topics set free joints,
and `joint_states` goes out every 1/rate on the node's clock (sim time with use_sim_time). A description that
cannot be used is reported and the previous one kept.

As upstream, the node declares every override it is given (automatically_declare_parameters_from_overrides:
`zeros.<joint>`, `dependent_joints.<joint>.*`) and then its own eight parameters, each typed by its default
(`source_list`'s `[]` is a byte array in rclpy, as in ROS).
"""

from __future__ import annotations

import threading
from pathlib import Path
from typing import Any

from diffctl.client.interfaces import cls
from diffctl.description.robot_files import read_description_text
from diffctl.errors import DescriptionError
from diffctl.joint_state_publisher.joints import parse_joints
from diffctl.joint_state_publisher.params import JspParams
from diffctl.joint_state_publisher.state import JointStates

NODE_NAME = "joint_state_publisher"
# name, default, rcl_interfaces/msg/ParameterType
DECLARED = (("publish_default_efforts", False, 1), ("publish_default_positions", True, 1),
            ("publish_default_velocities", False, 1), ("rate", 10, 2), ("source_list", [], 9),
            ("use_mimic_tags", True, 1), ("use_smallest_joint_limits", True, 1), ("delta", 0.0, 3))


def make_node(description: str | None, source: str) -> Any:
    from diffctl.client.exceptions import ParameterAlreadyDeclaredException
    from diffctl.client.node import Node
    from diffctl.client.qos import DurabilityPolicy, QoSProfile

    node = Node(NODE_NAME, automatically_declare_parameters_from_overrides=True)
    descriptor = cls("rcl_interfaces/msg/ParameterDescriptor")
    for name, default, ptype in DECLARED:
        try:
            node.declare_parameter(name, default, descriptor(type=ptype))
        except ParameterAlreadyDeclaredException:
            pass
    params = JspParams.from_dict({n: p.value for n, p in node.get_parameters_by_prefix("").items()})
    log = node.get_logger()
    lock = threading.Lock()
    states: list[JointStates] = []
    joint_state = cls("sensor_msgs/msg/JointState")

    def configure(text: str, where: str = "robot_description") -> None:
        joints = parse_joints(text, params, where)
        with lock:
            states[:] = [JointStates(joints, params)]
        log.info(f"publishing {len(joints.order)} joints ({len(joints.dependent)} dependent)")

    def on_description(msg: Any) -> None:
        try:
            configure(str(msg.data))
        except DescriptionError as e:
            log.warning(f"robot_description ignored: {e}")

    def on_source(msg: Any) -> None:
        with lock:
            if states:
                states[0].merge(list(msg.name), [float(x) for x in msg.position],
                                [float(x) for x in msg.velocity], [float(x) for x in msg.effort])

    def on_timer() -> None:
        with lock:
            if not states:
                return
            if params.delta_rad > 0:
                states[0].sweep(params.delta_rad)
            fields = states[0].message()
        if fields is not None:
            msg = joint_state(**fields)
            msg.header.stamp = node.get_clock().now().to_msg()
            pub.publish(msg)

    if description is not None:
        configure(description, source)
    else:
        log.info("Waiting for robot_description to be published on the robot_description topic...")
    node.create_subscription(cls("std_msgs/msg/String"), "robot_description", on_description,
                             QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL))
    for topic in params.source_list:
        node.create_subscription(joint_state, topic, on_source, 10)
    pub = node.create_publisher(joint_state, "joint_states", 10)
    node.create_timer(1.0 / params.rate_hz, on_timer)
    return node


def run(description_file: Path | None = None) -> int:
    """Check the parameters given and the description file before anything touches the bus, then run."""
    from diffctl import ros_args
    from diffctl.client import component

    description = None
    if description_file is not None:
        # A .xacro file (or xacro-namespaced URDF) is expanded as robot_state_publisher's launch files do.
        description = read_description_text(description_file)
        parse_joints(description, JspParams.from_dict(ros_args.current(NODE_NAME).params), str(description_file))
    return component.run(lambda: make_node(description, str(description_file or "")))
