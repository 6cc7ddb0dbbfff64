"""The joint_state_publisher node on the bus: reads /robot_description (latched) or a file, merges the
source_list topics, and publishes `joint_states` every 1/rate on the node's clock (sim time with
use_sim_time). A description that cannot be used is reported and the previous one kept."""

from __future__ import annotations

import threading
from pathlib import Path
from typing import Any

from diffctl.description.robot_files import read_description_text
from diffctl.errors import DescriptionError
from diffctl.joint_state_publisher.joints import parse_joints
from diffctl.joint_state_publisher.params import JspParams
from diffctl.joint_state_publisher.state import JointStates

NODE_NAME = "joint_state_publisher"


class JointStatePublisher:
    def __init__(self, node: Any, params: JspParams, description: str | None = None, source: str = "") -> None:
        self.node = node
        self.params = params
        self.lock = threading.Lock()
        self.states: JointStates | None = None
        if description is not None:
            self.configure(description, source)
        else:
            node.log.info("waiting for robot_description to be published on the robot_description topic...")
        node.create_subscription("robot_description", "std_msgs/msg/String", self.on_description, latched=True)
        for topic in params.source_list:
            node.create_subscription(topic, "sensor_msgs/msg/JointState", self.on_source)
        self.pub = node.create_publisher("joint_states", "sensor_msgs/msg/JointState", depth=10)
        node.create_timer(1.0 / params.rate_hz, self.on_timer)

    def configure(self, description: str, source: str = "robot_description") -> None:
        joints = parse_joints(description, self.params, source)
        with self.lock:
            self.states = JointStates(joints, self.params)
        self.node.log.info(f"publishing {len(joints.order)} joints ({len(joints.dependent)} dependent)")

    def on_description(self, msg: Any) -> None:
        try:
            self.configure(str(msg.data))
        except DescriptionError as e:
            self.node.log.warn(f"robot_description ignored: {e}")

    def on_source(self, msg: Any) -> None:
        with self.lock:
            if self.states is not None:
                self.states.merge(
                    list(msg.name), [float(x) for x in msg.position], [float(x) for x in msg.velocity],
                    [float(x) for x in msg.effort],
                )

    def on_timer(self) -> None:
        with self.lock:
            if self.states is None:
                return
            if self.params.delta_rad > 0:
                self.states.sweep(self.params.delta_rad)
            fields = self.states.message()
        if fields is None:
            return
        stamp_ns = self.node.now_ns()
        header = {"stamp": {"sec": stamp_ns // 1_000_000_000, "nanosec": stamp_ns % 1_000_000_000}}
        self.pub.publish({"header": header, **fields})


def run(params: dict[str, Any], description_file: Path | None = None) -> None:
    """Validate the parameters and the description file, then publish until SIGINT/SIGTERM."""
    from diffctl.bus import Node, close_session

    jsp_params = JspParams.from_dict(params)
    description = None
    if description_file is not None:
        # A .xacro file (or xacro-namespaced URDF) is expanded as robot_state_publisher's launch files do.
        description = read_description_text(description_file)
        parse_joints(description, jsp_params, str(description_file))  # a bad file starts nothing
    node = Node.from_ros_args(NODE_NAME, params={**params, "use_sim_time": jsp_params.use_sim_time})
    try:
        JointStatePublisher(node, jsp_params, description, str(description_file or ""))
        node.spin()
    finally:
        node.close()
        # Zenoh's callback threads are not daemons: close the session before the interpreter joins them.
        close_session()
