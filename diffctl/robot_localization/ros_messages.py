"""Message ↔ number conversions the robot_localization nodes share (stamps, poses, transforms, the tf tree)."""

from __future__ import annotations

from typing import Any

from diffctl.interfaces import get_interface
from diffctl.robot_localization.rotations import Rigid
from diffctl.tf2.buffer_core import BufferCore
from diffctl.tf2.exceptions import TransformException


def stamp_ns(stamp: Any) -> int:
    return int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)


def time_msg(ns: int) -> Any:
    return get_interface("builtin_interfaces/msg/Time")(sec=ns // 1_000_000_000, nanosec=ns % 1_000_000_000)


def quat_of(q: Any) -> tuple[float, float, float, float]:
    return (float(q.x), float(q.y), float(q.z), float(q.w))


def xyz_of(v: Any) -> tuple[float, float, float]:
    return (float(v.x), float(v.y), float(v.z))


def transform_msg(stamp: int, parent: str, child: str, t: Rigid) -> Any:
    ts = get_interface("geometry_msgs/msg/TransformStamped")()
    ts.header.stamp = time_msg(stamp)
    ts.header.frame_id = parent
    ts.child_frame_id = child
    ts.transform.translation.x, ts.transform.translation.y, ts.transform.translation.z = (float(v) for v in t.trans)
    r = ts.transform.rotation
    r.x, r.y, r.z, r.w = t.quat()
    return ts


class TfTree:
    """/tf and /tf_static into a tf2 buffer, and the lookups robot_localization makes: at the time asked,
    else the latest transform, else nothing."""

    def __init__(self, node: Any) -> None:
        from diffctl.client.qos import DurabilityPolicy, QoSProfile

        self.buffer = BufferCore()
        tf = get_interface("tf2_msgs/msg/TFMessage")
        node.create_subscription(tf, "/tf", self._on_tf, QoSProfile(depth=100))
        node.create_subscription(tf, "/tf_static", self._on_static,
                                 QoSProfile(depth=100, durability=DurabilityPolicy.TRANSIENT_LOCAL))

    def _insert(self, msg: Any, static: bool) -> None:
        for t in msg.transforms:
            self.buffer.set_transform(t.header.frame_id, t.child_frame_id, stamp_ns(t.header.stamp),
                                      xyz_of(t.transform.translation), quat_of(t.transform.rotation),
                                      is_static=static)

    def _on_tf(self, msg: Any) -> None:
        self._insert(msg, False)

    def _on_static(self, msg: Any) -> None:
        self._insert(msg, True)

    def clear(self) -> None:
        self.buffer.clear()

    def lookup(self, target: str, source: str, time_ns: int) -> Rigid | None:
        """The transform taking `source` coordinates to `target` at `time_ns`, else the latest one."""
        for t in (time_ns, 0):
            try:
                _, xyz, q = self.buffer.lookup_transform(target, source, t)
            except TransformException:
                continue
            return Rigid.from_xyz_quat(xyz, q)
        return None
