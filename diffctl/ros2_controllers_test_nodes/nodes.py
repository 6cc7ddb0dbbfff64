"""publisher_forward_position_controller and publisher_joint_trajectory_controller (ros2_controllers 4.x, Jazzy).

Each cycles through the goals named by `goal_names`, one every `wait_sec_between_publish` seconds: the forward
one publishes a goal's values as std_msgs/Float64MultiArray on `publish_topic`; the trajectory one publishes a
one-point trajectory_msgs/JointTrajectory (time_from_start 4 s) on `/<controller_name>/joint_trajectory`, and
with `check_starting_point` first waits for a joint_states message within `starting_point_limits.<joint>`.
Node names, parameters, topics, depths and log lines are upstream's.
"""

from __future__ import annotations

import math
from typing import Any

from diffctl.errors import ConfigError
from diffctl.interfaces import get_interface as msg

TRAJECTORY_FIELDS = ("positions", "velocities", "accelerations", "effort")
STARTING_LIMIT = 2 * 3.14159  # upstream's default window, ±2·3.14159 rad


def _goal_values(node: Any, name: str) -> list[float]:
    from diffctl.client.parameter import Parameter

    node.declare_parameter(name, Parameter.Type.DOUBLE_ARRAY)
    values = node.get_parameter(name).value
    if not values:
        raise ConfigError(f'Values for goal "{name}" not set!',
                          hint=f"give parameter {name} a list of doubles, one per joint")
    return [float(v) for v in values]


def forward_position(node: Any) -> None:
    topic = node.declare_parameter("publish_topic", "/position_commands").value
    period_s = node.declare_parameter("wait_sec_between_publish", 5).value
    names = list(node.declare_parameter("goal_names", ["pos1", "pos2"]).value)
    goals = [_goal_values(node, name) for name in names]
    log = node.get_logger()
    log.info(f"Publishing {len(names)} goals on topic '{topic}' every {period_s} s'")
    array = msg("std_msgs/msg/Float64MultiArray")
    pub = node.create_publisher(array, topic, 1)
    turn = [0]

    def publish() -> None:
        values = goals[turn[0]]
        log.info(f"Publishing: \"array('d', {values})\"")  # rclpy's message holds an array.array('d')
        pub.publish(array(data=values))
        turn[0] = (turn[0] + 1) % len(goals)

    node.create_timer(float(period_s), publish)


def _trajectory_point(node: Any, name: str, joints: list[str]) -> Any | None:
    """The goal `name`'s point, from `<name>.positions` … `<name>.effort` of one value per joint; None if none fits."""
    from diffctl.client.parameter import Parameter

    node.declare_parameter(name, Parameter.Type.DOUBLE_ARRAY)
    point = msg("trajectory_msgs/msg/JointTrajectoryPoint")()
    usable = False
    for field in TRAJECTORY_FIELDS:
        values = node.declare_parameter(f"{name}.{field}", [0.0]).value
        if len(values) == len(joints):
            setattr(point, field, [float(v) for v in values])
            usable = True
    if not usable:
        return None
    point.time_from_start.sec = 4
    return point


def joint_trajectory(node: Any) -> None:
    controller = node.declare_parameter("controller_name", "position_trajectory_controller").value
    period_s = node.declare_parameter("wait_sec_between_publish", 6).value
    names = list(node.declare_parameter("goal_names", ["pos1", "pos2"]).value)
    joints = list(node.declare_parameter("joints", [""]).value)
    check = bool(node.declare_parameter("check_starting_point", False).value)
    log = node.get_logger()
    if not joints:
        raise ConfigError('"joints" parameter is not set!')
    limits: dict[str, list[float]] = {}
    if check:
        for joint in joints:
            window = list(node.declare_parameter(f"starting_point_limits.{joint}",
                                                 [-STARTING_LIMIT, STARTING_LIMIT]).value)
            if len(window) != 2:
                raise ConfigError('"starting_point" parameter is not set correctly!',
                                  hint=f"starting_point_limits.{joint} takes [lower, upper]")
            limits[joint] = window
    goals = []
    for name in names:
        point = _trajectory_point(node, name, joints)
        if point is None:
            log.warning(f'Goal "{name}" definition is wrong. This goal will not be used. Use the following '
                        "structure: \n<goal_name>:\n  positions: [joint1, joint2, joint3, ...]\n  velocities: "
                        "[v_joint1, v_joint2, ...]\n  accelerations: [a_joint1, a_joint2, ...]\n  effort: "
                        "[eff_joint1, eff_joint2, ...]")
            continue
        goals.append(point)
        log.info(f'Goal "{name}" has definition {point}')
    if not goals:
        log.error("No valid goal found. Exiting...")
        raise SystemExit(1)
    topic = f"/{controller}/joint_trajectory"
    log.info(f"Publishing {len(names)} goals on topic '{topic}' every {period_s} s")
    trajectory = msg("trajectory_msgs/msg/JointTrajectory")
    pub = node.create_publisher(trajectory, topic, 1)
    state = {"turn": 0, "seen": False, "ok": not check}

    def publish() -> None:
        if state["ok"]:
            goal = goals[state["turn"]]
            log.info(f"Sending goal {goal}.")
            pub.publish(trajectory(joint_names=joints, points=[goal]))
            state["turn"] = (state["turn"] + 1) % len(goals)
        elif not state["seen"]:
            log.warning('Start configuration could not be checked! Check "joint_state" topic!')
        else:
            log.warning("Start configuration is not within configured limits!")

    def on_joint_states(m: Any) -> None:
        if state["seen"]:
            return  # only the first message decides, as upstream
        inside = True
        for joint, position in zip(m.name, m.position, strict=False):
            window = limits.get(joint)
            if window is not None and not (window[0] <= position <= window[1] and math.isfinite(position)):
                log.warning(f"Starting point limits exceeded for joint {joint} !")
                inside = False
        state["ok"], state["seen"] = inside, True

    if check:
        node.create_subscription(msg("sensor_msgs/msg/JointState"), "joint_states", on_joint_states, 10)
    node.create_timer(float(period_s), publish)


NODES = {
    "publisher_forward_position_controller": ("publisher_forward_position_controller", forward_position),
    "publisher_joint_trajectory_controller": ("publisher_position_trajectory_controller", joint_trajectory),
}


def run(executable: str) -> int:
    from diffctl.client import component
    from diffctl.client.node import Node

    node_name, build = NODES[executable]

    def make() -> Any:
        node = Node(node_name)
        build(node)
        return node

    return component.run(make)
