"""Publishing a velocity command as geometry_msgs/msg/Twist or TwistStamped, the two forms teleop tools offer.

Values are checked here, the last step before the bus: a non-finite component never leaves the process.
"""

from __future__ import annotations

import math
from typing import Any

from diffctl.client.interfaces import cls
from diffctl.errors import MessageError

TWIST = "geometry_msgs/msg/Twist"
TWIST_STAMPED = "geometry_msgs/msg/TwistStamped"

Vec3 = tuple[float, float, float]


class TwistCommand:
    def __init__(self, node: Any, topic: str, *, stamped: bool, frame_id: str = "") -> None:
        """`node`: a client Node."""
        self.node = node
        self.stamped = stamped
        self.frame_id = frame_id
        self.typename = TWIST_STAMPED if stamped else TWIST
        self.pub = node.create_publisher(cls(self.typename), topic, 10)
        self._vector3 = cls("geometry_msgs/msg/Vector3")
        self._twist = cls(TWIST)
        self._stamped = cls(TWIST_STAMPED)
        self._header = cls("std_msgs/msg/Header")

    @property
    def topic(self) -> str:
        return self.node.resolve_topic_name(self.pub.topic_name)

    def message(self, linear_m_s: Vec3, angular_rad_s: Vec3) -> Any:
        values = (*linear_m_s, *angular_rad_s)
        if not all(math.isfinite(v) for v in values):
            raise MessageError(f"velocity command {values} is not finite")
        (lx, ly, lz), (ax, ay, az) = (map(float, linear_m_s), map(float, angular_rad_s))
        twist = self._twist(linear=self._vector3(x=lx, y=ly, z=lz), angular=self._vector3(x=ax, y=ay, z=az))
        if not self.stamped:
            return twist
        stamp = self.node.get_clock().now().to_msg()
        return self._stamped(header=self._header(stamp=stamp, frame_id=self.frame_id), twist=twist)

    def publish(self, linear_m_s: Vec3, angular_rad_s: Vec3) -> None:
        self.pub.publish(self.message(linear_m_s, angular_rad_s))

    def stop(self) -> None:
        self.publish((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
