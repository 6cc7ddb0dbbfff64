"""Publishing a velocity command as geometry_msgs/msg/Twist or TwistStamped, the two forms teleop tools offer.

Values are checked here, the last step before the bus: a non-finite component never leaves the process.
"""

from __future__ import annotations

import math
from typing import Any

from diffctl.bus import Node
from diffctl.errors import MessageError
from diffctl.interfaces import types

TWIST = "geometry_msgs/msg/Twist"
TWIST_STAMPED = "geometry_msgs/msg/TwistStamped"

Vec3 = tuple[float, float, float]


class TwistCommand:
    def __init__(self, node: Node, topic: str, *, stamped: bool, frame_id: str = "") -> None:
        self.node = node
        self.stamped = stamped
        self.frame_id = frame_id
        self.typename = TWIST_STAMPED if stamped else TWIST
        self.pub = node.create_publisher(topic, self.typename)
        self._vector3 = types.get_class("geometry_msgs/msg/Vector3")
        self._twist = types.get_class(TWIST)
        self._stamped = types.get_class(TWIST_STAMPED)
        self._header = types.get_class("std_msgs/msg/Header")

    @property
    def topic(self) -> str:
        return self.pub.topic

    def message(self, linear_m_s: Vec3, angular_rad_s: Vec3) -> Any:
        values = (*linear_m_s, *angular_rad_s)
        if not all(math.isfinite(v) for v in values):
            raise MessageError(f"velocity command {values} is not finite")
        twist = self._twist(
            linear=self._vector3(*map(float, linear_m_s)), angular=self._vector3(*map(float, angular_rad_s))
        )
        if not self.stamped:
            return twist
        return self._stamped(header=self._header(stamp=self.node.now(), frame_id=self.frame_id), twist=twist)

    def publish(self, linear_m_s: Vec3, angular_rad_s: Vec3) -> None:
        self.pub.publish(self.message(linear_m_s, angular_rad_s))

    def stop(self) -> None:
        self.publish((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
