"""Gazebo's TrackedVehicle system (`gz-sim-tracked-vehicle-system`): a twist turned into left and right track speeds.

SDF parameters as gz-sim 8 reads them: `left_track` and `right_track` (repeatable; each with `link`, and
optionally `velocity_topic` and `center_of_rotation_topic`, the topics of the track's TrackController),
`tracks_separation` (1 m), `steering_efficiency` (0.5; gz.msgs.Double on `steering_efficiency_topic`, default
/model/<m>/steering_efficiency), `linear_velocity` and `angular_velocity` limiters (each with
`[min|max]_[velocity|acceleration|jerk]`), `odom_publish_frequency` (50 Hz), `topic` (/model/<m>/cmd_vel),
`odom_topic`, `tf_topic`, `frame_id`, `child_frame_id` (none unless it or `body_link` is given), `body_link`.
`track_height` is documented but, as in gz-sim 8, never read (it cancels out of the odometry).
Whenever the limited twist changes: track speeds v ∓ ω · separation / (2 · steering efficiency) and a centre of
rotation on the body's y axis at v / ω (none for ω = 0, the body's origin for v = 0), a point in the world until
the next change, sent to each track (the TrackController of the same model directly, others on their topics).
Odometry is dead reckoning from the commanded track speeds every step (gz-sim's), as a differential drive.
"""

from __future__ import annotations

import math
from typing import Any

from lxml import etree

from diffctl.description.model import Plugin
from diffctl.errors import DescriptionError
from diffctl.sim.entity import Entity
from diffctl.sim.plugins.attachments import Attachments
from diffctl.sim.plugins.base import PluginContext, SystemPlugin, float_param, rate_period_ns
from diffctl.sim.plugins.diff_drive_math import Limits, Odometry, limit_speed
from diffctl.sim.plugins.system_support import OdometryNames, OdometryOutput, planar_twist, valid_topic
from diffctl.sim.plugins.track_controller import TrackController

# gz-sim 8 never reads <track_height>: its odometry runs on its default height (0.2 m), whose half turns track
# travel into wheel angles and back.
ODOMETRY_WHEEL_RADIUS_M = 0.1


def _limits(root: etree._Element, tag: str) -> Limits:
    el = root.find(tag)
    if el is None:
        return Limits()

    def num(name: str) -> float | None:
        text = el.findtext(name)
        return None if text is None else float(text)

    return Limits(*(num(f"{m}_{kind}") for kind in ("velocity", "acceleration", "jerk") for m in ("min", "max")))


class TrackedVehicle(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, plugin: Plugin, tracks: list[TrackController]) -> None:
        self.ctx, self.entity = ctx, entity
        source, name = entity.model.source, entity.name
        root = etree.fromstring(plugin.xml.encode()) if plugin.xml else etree.Element("plugin")
        try:
            self.linear, self.angular = _limits(root, "linear_velocity"), _limits(root, "angular_velocity")
        except ValueError as e:
            message = f"plugin {plugin.name!r}: a velocity limit is not a number ({e})"
            raise DescriptionError(message, source=source or None) from None
        self.sides: dict[str, list[tuple[str, str, str]]] = {}
        for side in ("left", "right"):
            self.sides[side] = []
            for el in root.findall(f"{side}_track"):
                link = (el.findtext("link") or "").strip()
                topic = el.findtext("velocity_topic") or f"/model/{name}/link/{link}/track_cmd_vel"
                cor = el.findtext("center_of_rotation_topic") or (
                    f"/model/{name}/link/{link}/track_cmd_center_of_rotation"
                )
                self.sides[side].append((link, valid_topic(topic), valid_topic(cor)))
        self.separation_m = float_param(plugin, "tracks_separation", 1.0, source=source) or 1.0
        self.efficiency = float_param(plugin, "steering_efficiency", 0.5, source=source) or 0.5
        self.active = bool(self.sides["left"] and self.sides["right"])
        body_link = plugin.get("body_link")
        self.body_link = body_link or entity.model.canonical_link or entity.model.root_link()
        self.frame_id = plugin.get("frame_id") or f"{name}/odom"
        self.child_frame_id = plugin.get("child_frame_id") or (f"{name}/{body_link}" if body_link else None)
        self.tracks = {t.link: t for t in tracks}
        self.target = (0.0, 0.0)
        self._last = [(0.0, 0.0), (0.0, 0.0)]
        self._new = False
        self._speeds = (0.0, 0.0)
        self._wheel = [0.0, 0.0]  # integrated commanded track travel, as wheel angles
        self.center: tuple[float, float, float] | None = None
        self.odom = Odometry(self.separation_m, ODOMETRY_WHEEL_RADIUS_M)
        self._dt_s = ctx.stepper.step_ns * 1e-9
        self.attached = Attachments(ctx)
        self._pubs: dict[str, Any] = {}
        self._cor_pubs: dict[str, Any] = {}
        self.output: OdometryOutput | None = None
        if not self.active:
            return
        a = self.attached
        a.subscribe(valid_topic(plugin.get("topic") or f"/model/{name}/cmd_vel"), "gz.msgs.Twist", self.on_twist)
        se_topic = valid_topic(plugin.get("steering_efficiency_topic") or f"/model/{name}/steering_efficiency")
        a.subscribe(se_topic, "gz.msgs.Double", self.on_efficiency)
        names = OdometryNames(valid_topic(plugin.get("odom_topic") or f"/model/{name}/odometry"),
                              valid_topic(plugin.get("tf_topic") or f"/model/{name}/tf"), self.frame_id,
                              self.child_frame_id)
        self.output = OdometryOutput(a, names)
        if ctx.transport is not None:
            for side in self.sides.values():
                for link, topic, cor_topic in side:
                    if link not in self.tracks:
                        self._pubs[link] = a.publisher(topic, "gz.msgs.Double")
                        self._cor_pubs[link] = a.publisher(cor_topic, "gz.msgs.Vector3d")
        a.each_step(self._step)
        hz = float_param(plugin, "odom_publish_frequency", 50.0, source=source) or 50.0
        a.every(f"tracked:{name}", rate_period_ns(hz, ctx.stepper.step_ns), self._odometry)

    def on_twist(self, fields: dict[str, Any]) -> None:
        linear, _, angular = planar_twist(fields)
        self.command(linear, angular)

    def on_efficiency(self, fields: dict[str, Any]) -> None:
        value = float(fields.get("data", 0.0) or 0.0)
        if math.isfinite(value) and value > 0:
            self.efficiency = value
            self._new = True

    def command(self, linear_m_s: float, angular_rad_s: float) -> None:
        if math.isfinite(linear_m_s) and math.isfinite(angular_rad_s):
            self.target = (linear_m_s, angular_rad_s)
            self._new = True

    def _step(self) -> None:
        (v0, w0), (v1, w1) = self._last
        v = limit_speed(self.target[0], v0, v1, self._dt_s, self.linear)
        w = limit_speed(self.target[1], w0, w1, self._dt_s, self.angular)
        send = self._new or abs(v - v0) > 1e-6 or abs(w - w0) > 1e-6
        self._new = False
        self._last = [(v, w), (v0, w0)]
        if send:
            turn = w * self.separation_m / (2.0 * self.efficiency)
            self._speeds = (v - turn, v + turn)
            self.center = self._center(v, w)
            for side, speed in zip(("left", "right"), self._speeds, strict=True):
                for link, _topic, _cor in self.sides[side]:
                    track = self.tracks.get(link)
                    if track is not None:
                        track.command(speed)
                        track.set_center(self.center)
                    elif link in self._pubs:
                        self._pubs[link].publish({"data": speed})
                        x, y, z = self.center
                        self._cor_pubs[link].publish({"x": x, "y": y, "z": z})
        radius = ODOMETRY_WHEEL_RADIUS_M
        self._wheel = [
            self._wheel[0] + self._speeds[0] / radius * self._dt_s,
            self._wheel[1] + self._speeds[1] / radius * self._dt_s,
        ]
        after_step_s = (self.ctx.stepper.sim_time_ns + self.ctx.stepper.step_ns) * 1e-9
        self.odom.update(self._wheel[0], self._wheel[1], after_step_s)

    def _center(self, v: float, w: float) -> tuple[float, float, float]:
        """The centre of rotation in the world: on the body's y axis at v / ω (infinitely far for ω ≈ 0, the
        body's origin for v ≈ 0), as gz-sim computes it, non-finite components and all."""
        radius = math.inf if abs(w) < 1e-6 else 0.0 if abs(v) < 1e-6 else v / w
        pose = self.entity.link_pose(self.body_link)
        y_axis = pose.rotate((0.0, 1.0, 0.0))
        return (
            y_axis[0] * radius + pose.xyz[0],
            y_axis[1] * radius + pose.xyz[1],
            y_axis[2] * radius + pose.xyz[2],
        )

    def _odometry(self, sim_time_ns: int) -> None:
        if self.output is not None:
            o = self.odom
            self.output.publish(sim_time_ns, (o.x_m, o.y_m, o.heading_rad), (o.linear_m_s, 0.0, o.angular_rad_s))

    def reset(self) -> None:
        self.odom.reset()
        self.target, self._speeds = (0.0, 0.0), (0.0, 0.0)
        self._last = [(0.0, 0.0), (0.0, 0.0)]
        self._wheel = [0.0, 0.0]
        self.center = None
        self._new = True

    def close(self) -> None:
        self.attached.close()
