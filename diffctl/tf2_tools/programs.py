"""The two tf2_ros programs as client nodes: static_transform_publisher (one latched /tf_static transform, as
tf2_ros::StaticTransformBroadcasterNode, its values read-only parameters) and tf2_echo (a listener on /tf and
/tf_static printing a lookup at its rate, on the wall clock). Exit codes and messages as the C++ programs'."""

from __future__ import annotations

import random
import sys
import time
from typing import Any

from diffctl.tf2_tools.args import STATIC_USAGE, ArgsError, EchoUsage, parse_echo, parse_static
from diffctl.tf2_tools.echo_format import echo_block

TF_TYPE = "tf2_msgs/msg/TFMessage"
_NAME_CHARS = "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"


def _rcutils_log(level: str, text: str) -> None:
    # RCUTILS_LOG_* without a node: the logger name is empty
    sys.stderr.write(f"[{level}] [{time.time_ns() / 1e9:.6f}] []: {text}\n")
    sys.stderr.flush()


def unique_node_name() -> str:
    """static_transform_publisher_ and 16 random letters or digits, as the node names itself."""
    return "static_transform_publisher_" + "".join(random.choice(_NAME_CHARS) for _ in range(16))


def static_transform_publisher(argv: list[str]) -> int:
    """Publish one static transform on /tf_static until stopped; 1 with the usage on bad arguments."""
    try:
        st = parse_static(argv, warn=lambda text: _rcutils_log("WARN", text))
    except ArgsError as e:
        _rcutils_log("ERROR", f"error parsing command line arguments: {e}")
        print(STATIC_USAGE, flush=True)
        return 1
    if st.help:
        print(STATIC_USAGE, flush=True)
        return 0
    from diffctl.client import component

    # The program's values are the node's parameter overrides: they win over --ros-args files and -p.
    values = {"translation.x": st.translation[0], "translation.y": st.translation[1],
              "translation.z": st.translation[2], "rotation.x": st.rotation[0], "rotation.y": st.rotation[1],
              "rotation.z": st.rotation[2], "rotation.w": st.rotation[3], "frame_id": st.frame_id,
              "child_frame_id": st.child_frame_id}
    return component.run(lambda: _static_node(values))


def _static_node(values: dict[str, Any]) -> Any:
    from diffctl.client.interfaces import cls
    from diffctl.client.node import Node
    from diffctl.client.parameter import Parameter
    from diffctl.client.qos import DurabilityPolicy, QoSPolicyKind, QoSProfile
    from diffctl.client.qos_overriding_options import QoSOverridingOptions

    node = Node(unique_node_name(), client_library="rclcpp",
                parameter_overrides=[Parameter(n, value=v) for n, v in values.items()])
    read_only = cls("rcl_interfaces/msg/ParameterDescriptor")(read_only=True)
    defaults = {"translation.x": 0.0, "translation.y": 0.0, "translation.z": 0.0, "rotation.x": 0.0,
                "rotation.y": 0.0, "rotation.z": 0.0, "rotation.w": 1.0, "frame_id": "/frame",
                "child_frame_id": "/child"}
    p = {name: node.declare_parameter(name, default, read_only).value for name, default in defaults.items()}
    if p["frame_id"] == p["child_frame_id"]:
        node.get_logger().error(f"cannot publish static transform from '{p['frame_id']}' to "
                                f"'{p['child_frame_id']}', exiting")
        node.destroy_node()
        raise SystemExit(1)
    overrides = QoSOverridingOptions([QoSPolicyKind.DEPTH, QoSPolicyKind.HISTORY, QoSPolicyKind.RELIABILITY])
    pub = node.create_publisher(cls(TF_TYPE), "/tf_static",
                                QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL),
                                qos_overriding_options=overrides)
    stamped = cls("geometry_msgs/msg/TransformStamped")()
    stamped.header.stamp = node.get_clock().now().to_msg()
    stamped.header.frame_id, stamped.child_frame_id = p["frame_id"], p["child_frame_id"]
    tr, rot = stamped.transform.translation, stamped.transform.rotation
    tr.x, tr.y, tr.z = p["translation.x"], p["translation.y"], p["translation.z"]
    rot.x, rot.y, rot.z, rot.w = p["rotation.x"], p["rotation.y"], p["rotation.z"], p["rotation.w"]
    pub.publish(cls(TF_TYPE)(transforms=[stamped]))
    node.get_logger().info(
        "Spinning until stopped - publishing transform\n"
        f"translation: ('{p['translation.x']:f}', '{p['translation.y']:f}', '{p['translation.z']:f}')\n"
        f"rotation: ('{p['rotation.x']:f}', '{p['rotation.y']:f}', '{p['rotation.z']:f}', "
        f"'{p['rotation.w']:f}')\nfrom '{p['frame_id']}' to '{p['child_frame_id']}'"
    )
    return node


class _Listener:
    """tf2_ros::TransformListener's two subscriptions feeding a BufferCore."""

    def __init__(self, node: Any) -> None:
        from diffctl.client.interfaces import cls
        from diffctl.client.qos import DurabilityPolicy, QoSProfile
        from diffctl.tf2.buffer_core import BufferCore

        self.core = BufferCore()
        node.create_subscription(cls(TF_TYPE), "/tf", lambda m: self._on(m, False), 100)
        node.create_subscription(cls(TF_TYPE), "/tf_static", lambda m: self._on(m, True),
                                 QoSProfile(depth=100, durability=DurabilityPolicy.TRANSIENT_LOCAL))

    def _on(self, msg: Any, static: bool) -> None:
        for t in msg.transforms:
            tr, rot = t.transform.translation, t.transform.rotation
            stamp = int(t.header.stamp.sec) * 1_000_000_000 + int(t.header.stamp.nanosec)
            self.core.set_transform(t.header.frame_id, t.child_frame_id, stamp, (tr.x, tr.y, tr.z),
                                    (rot.x, rot.y, rot.z, rot.w), "Authority undetectable", static)


def tf2_echo(argv: list[str]) -> int:
    """Print the transform from source_frame to target_frame at the rate given (1 Hz), until stopped."""
    try:
        a = parse_echo(argv)
    except EchoUsage as e:
        (sys.stdout if e.code == 1 else sys.stderr).write(str(e) + ("" if e.code == 1 else "\n"))
        return e.code
    from diffctl.client import component

    return component.run(lambda: _echo_node(a.source_frame, a.target_frame, a.rate_hz))


def _echo_node(source: str, target: str, rate_hz: float) -> Any:
    from diffctl.client.clock import Clock
    from diffctl.client.clock_type import ClockType
    from diffctl.client.node import Node
    from diffctl.tf2.exceptions import TransformException

    node = Node("tf2_echo", client_library="rclcpp")
    listener = _Listener(node)
    found = False

    def tick() -> None:
        nonlocal found
        if not found:
            found, why = listener.core.can_transform(source, target, 0)
            if not found:
                node.get_logger().info(f"Waiting for transform {source} ->  {target}: {why}",
                                       throttle_duration_sec=1.0)
                return
        try:
            stamp, t, q = listener.core.lookup_transform(source, target, 0)
            sys.stdout.write(echo_block(stamp // 1_000_000_000, stamp % 1_000_000_000, t, q))
        except TransformException as ex:
            sys.stdout.write(f"Failure at {node.get_clock().now().nanoseconds / 1e9:.3f}\nException thrown:{ex}\n"
                             f"The current list of frames is:\n{listener.core.all_frames_as_string()}\n")
        sys.stdout.flush()

    node.create_timer(1.0 / rate_hz if rate_hz > 0 else 1.0, tick, clock=Clock(clock_type=ClockType.STEADY_TIME))
    return node
