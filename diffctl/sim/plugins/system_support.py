"""What Gazebo's model systems share: joints found by name (a missing one is warned about, as gz-sim does, and
the system idles), gz topic names made valid, a gz.msgs.Twist's planar components, and the wheel odometry drive
systems publish (its messages, and the publishers that send them while anyone listens)."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any

from diffctl.bus import gz
from diffctl.description.model import Plugin
from diffctl.errors import DescriptionError
from diffctl.sim.entity import Entity, JointHandle
from diffctl.sim.plugins.attachments import Attachments
from diffctl.sim.plugins.base import PluginContext, float_param
from diffctl.sim.plugins.diff_drive_math import Limits

_TOPIC_BAD = re.compile(r"[\s@]|:=|~")


def valid_topic(topic: str) -> str:
    """gz-transport's TopicUtils::AsValidTopic, as far as names met in practice go: blanks become '_', the
    characters it refuses are dropped, repeated slashes collapse; then the name as the node resolves it."""
    t = _TOPIC_BAD.sub(lambda m: "_" if m.group().isspace() else "", topic)
    return "/" + re.sub(r"/{2,}", "/", t).lstrip("/")  # gz-transport's fully qualified names start with '/'


def find_joints(
    ctx: PluginContext, entity: Entity, names: list[str] | tuple[str, ...], system: str
) -> list[JointHandle]:
    """The moving joints named, in order; each missing one is one warning (the system then does without it)."""
    out = []
    for name in names:
        if name in entity.joints:
            out.append(entity.joints[name])
            continue
        # gz-sim's JointPositionController also finds a scoped joint by its last name
        tail = [h for n, h in entity.joints.items() if n.rsplit("::", 1)[-1] == name]
        if tail:
            out.append(tail[0])
            continue
        ctx.log.warn(f"{system}: failed to find joint [{name}] for model [{entity.name}]")
    return out


def int_param(plugin: Plugin, tag: str, default: int, *, source: str) -> int:
    text = plugin.get(tag)
    if text is None:
        return default
    m = re.match(r"\s*([-+]?\d+)", text)  # std::stoi reads the leading integer
    if m is None:
        raise DescriptionError(
            f"plugin {plugin.name!r}: <{tag}> {text!r} is not an integer",
            source=source or None,
            field=f"plugin {plugin.filename}: {tag}",
        )
    return int(m.group(1))


def speed_limits(plugin: Plugin, source: str) -> Limits:
    """gz-math SpeedLimiter bounds from `[min|max]_[velocity|acceleration|jerk]`; an absent one is unbounded."""
    values = [
        float_param(plugin, f"{m}_{kind}", None, source=source)
        for kind in ("velocity", "acceleration", "jerk")
        for m in ("min", "max")
    ]
    return Limits(*values)


def finite_or_none(*values: float) -> bool:
    return all(math.isfinite(v) for v in values)


def planar_twist(fields: dict[str, Any]) -> tuple[float, float, float]:
    """(linear.x, linear.y, angular.z) of a gz.msgs.Twist's fields, an absent one 0."""
    lin, ang = fields.get("linear") or {}, fields.get("angular") or {}
    return float(lin.get("x", 0.0) or 0.0), float(lin.get("y", 0.0) or 0.0), float(ang.get("z", 0.0) or 0.0)


def odometry_messages(
    sim_time_ns: int,
    frame_id: str,
    child_frame_id: str | None,
    pose_xy_yaw: tuple[float, float, float],
    twist: tuple[float, float, float],
) -> tuple[dict[str, Any], dict[str, Any]]:
    """(gz.msgs.Odometry, gz.msgs.Pose_V) as gz-sim's drive systems publish them: planar pose, twist
    (linear x, linear y, angular z), and one tf pose carrying the odometry's header."""
    x, y, yaw = pose_xy_yaw
    header = gz.header(sim_time_ns, frame_id, child_frame_id)
    position = {"x": x, "y": y, "z": 0.0}
    orientation = {"x": 0.0, "y": 0.0, "z": math.sin(yaw / 2.0), "w": math.cos(yaw / 2.0)}
    odom = {
        "header": header,
        "pose": {"position": position, "orientation": orientation},
        "twist": {"linear": {"x": twist[0], "y": twist[1], "z": 0.0}, "angular": {"x": 0.0, "y": 0.0, "z": twist[2]}},
    }
    tf = {
        "header": gz.header(sim_time_ns),
        "pose": [{"header": header, "position": position, "orientation": orientation}],
    }
    return odom, tf


@dataclass(frozen=True)
class OdometryNames:
    """Where a drive system's odometry goes and in which frames."""

    odom_topic: str
    tf_topic: str
    frame_id: str
    child_frame_id: str | None

    @staticmethod
    def from_plugin(plugin: Plugin, model: str, canonical_link: str, *, tf_topic_as_given: bool = False
                    ) -> OdometryNames:
        """`odom_topic`, `tf_topic`, `frame_id`, `child_frame_id` with gz-sim's defaults under /model/<model>
        (`tf_topic_as_given`: a system that does not make its tf topic valid, as MecanumDrive)."""
        base = f"/model/{model}"
        tf_topic = plugin.get("tf_topic") or f"{base}/tf"
        return OdometryNames(
            odom_topic=valid_topic(plugin.get("odom_topic") or f"{base}/odometry"),
            tf_topic=tf_topic if tf_topic_as_given else valid_topic(tf_topic),
            frame_id=plugin.get("frame_id") or f"{model}/odom",
            child_frame_id=plugin.get("child_frame_id") or f"{model}/{canonical_link}",
        )


class OdometryOutput:
    """A drive system's odometry (gz.msgs.Odometry) and tf (gz.msgs.Pose_V) publishers; a sample is only made
    while one of them has a subscriber."""

    def __init__(self, attached: Attachments, names: OdometryNames) -> None:
        self._odom = attached.publisher(names.odom_topic, "gz.msgs.Odometry")
        self._tf = attached.publisher(names.tf_topic, "gz.msgs.Pose_V")
        self.names = names

    def publish(self, sim_time_ns: int, pose_xy_yaw: tuple[float, float, float],
                twist: tuple[float, float, float]) -> None:
        if not ((self._odom and self._odom.matched) or (self._tf and self._tf.matched)):
            return
        names = self.names
        odom, tf = odometry_messages(sim_time_ns, names.frame_id, names.child_frame_id, pose_xy_yaw, twist)
        if self._odom is not None:
            self._odom.publish(odom)
        if self._tf is not None:
            self._tf.publish(tf)
