"""Gazebo's OdometryPublisher system (`gz-sim-odometry-publisher-system`): ground-truth odometry of a model.

Parameters as gz-sim reads them: `<odom_frame>` (`<model>/odom`), `<robot_base_frame>` (`<model>/base_footprint`),
`<odom_publish_frequency>` (50 Hz), `<odom_topic>` (`/model/<model>/odometry`), `<odom_covariance_topic>`
(`/model/<model>/odometry_with_covariance`: the same odometry as gz.msgs.OdometryWithCovariance, both
covariances' diagonals the noise's variance, as gz-sim 8 publishes it), `<tf_topic>`
(`/model/<model>/pose`, a Pose_V of one pose odom_frame → robot_base_frame), `<dimensions>` (2 or 3, default 2),
`<xyz_offset>`, `<rpy_offset>` (applied to the model pose), `<gaussian_noise>` (standard deviation added to
the twist). In 2D the pose is flattened (z, roll, pitch 0) and the twist has only linear x/y and angular z;
in 3D all six. The twist is in the body frame, from the pose change between samples, averaged over the
last 10 samples as gz-sim's rolling means do. The first sample only initialises.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass

import numpy as np

from diffctl.bus import gz
from diffctl.description.model import Plugin
from diffctl.description.pose import Pose, quat_from_rpy, rpy_from_quat
from diffctl.errors import DescriptionError
from diffctl.sim.entity import Entity
from diffctl.sim.plugins.base import PluginContext, SystemPlugin, float_param, rate_period_ns

DEFAULT_RATE_HZ = 50.0
VELOCITY_WINDOW = 10


def _triple(plugin: Plugin, tag: str, source: str) -> tuple[float, float, float]:
    text = plugin.get(tag)
    if text is None:
        return (0.0, 0.0, 0.0)
    try:
        values = tuple(float(v) for v in text.split())
    except ValueError:
        values = ()
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise DescriptionError(
            f"plugin {plugin.name!r}: <{tag}> {text!r} is not three finite numbers",
            source=source or None,
            field=f"plugin {plugin.filename}: {tag}",
        )
    return values  # type: ignore[return-value]


@dataclass(frozen=True)
class OdometryPublisherParams:
    odom_frame: str
    robot_base_frame: str
    rate_hz: float
    odom_topic: str
    odom_covariance_topic: str
    tf_topic: str
    dimensions: int
    offset: Pose
    noise_std: float

    @staticmethod
    def from_plugin(plugin: Plugin, model: str, source: str = "") -> OdometryPublisherParams:
        dims_text = (plugin.get("dimensions") or "2").strip()
        if dims_text not in ("2", "3"):
            raise DescriptionError(
                f"plugin {plugin.name!r}: <dimensions> {dims_text!r} is not 2 or 3",
                source=source or None,
                field=f"plugin {plugin.filename}: dimensions",
                hint="valid: 2, 3",
            )
        rate = float_param(plugin, "odom_publish_frequency", DEFAULT_RATE_HZ, source=source, positive=True)
        noise = float_param(plugin, "gaussian_noise", 0.0, source=source)
        return OdometryPublisherParams(
            odom_frame=plugin.get("odom_frame") or f"{model}/odom",
            robot_base_frame=plugin.get("robot_base_frame") or f"{model}/base_footprint",
            rate_hz=rate or DEFAULT_RATE_HZ,
            odom_topic=plugin.get("odom_topic") or f"/model/{model}/odometry",
            odom_covariance_topic=plugin.get("odom_covariance_topic") or f"/model/{model}/odometry_with_covariance",
            tf_topic=plugin.get("tf_topic") or f"/model/{model}/pose",
            dimensions=int(dims_text),
            offset=Pose(_triple(plugin, "xyz_offset", source), quat_from_rpy(*_triple(plugin, "rpy_offset", source))),
            noise_std=abs(noise or 0.0),
        )


class OdometryPublisher(SystemPlugin):
    def __init__(
        self, ctx: PluginContext, entity: Entity, plugin: Plugin, rng: np.random.Generator | None = None
    ) -> None:
        self.ctx, self.entity = ctx, entity
        self.p = OdometryPublisherParams.from_plugin(plugin, entity.name, entity.model.source)
        self.topics = (self.p.odom_topic, self.p.odom_covariance_topic, self.p.tf_topic)
        self.rng = rng or np.random.default_rng(0)
        t = ctx.transport
        self._odom_pub = t.publisher(self.p.odom_topic, "gz.msgs.Odometry") if t else None
        self._cov_pub = t.publisher(self.p.odom_covariance_topic, "gz.msgs.OdometryWithCovariance") if t else None
        self._tf_pub = t.publisher(self.p.tf_topic, "gz.msgs.Pose_V") if t else None
        self._last: tuple[int, Pose] | None = None
        self.last_message: dict | None = None  # the latest sample, published or not
        self._lin: deque[tuple[float, float, float]] = deque(maxlen=VELOCITY_WINDOW)
        self._ang: deque[tuple[float, float, float]] = deque(maxlen=VELOCITY_WINDOW)
        period = rate_period_ns(self.p.rate_hz, ctx.stepper.step_ns)
        self._task = ctx.stepper.add_task(f"odometry_publisher:{entity.name}", period, self._publish)

    def pose(self) -> Pose:
        pose = self.entity.pose().compose(self.p.offset)
        if self.p.dimensions == 2:
            yaw = rpy_from_quat(pose.quat)[2]
            return Pose((pose.xyz[0], pose.xyz[1], 0.0), quat_from_rpy(0.0, 0.0, yaw))
        return pose

    def message(self, sim_time_ns: int) -> dict | None:
        """The Odometry sample at `sim_time_ns`, None on the first (which only initialises)."""
        pose = self.pose()
        last, self._last = self._last, (sim_time_ns, pose)
        if last is None or sim_time_ns <= last[0]:
            return None
        dt = (sim_time_ns - last[0]) * 1e-9
        prev = last[1]
        # Body-frame velocities from the pose change over the interval.
        d_world = tuple((a - b) / dt for a, b in zip(pose.xyz, prev.xyz, strict=True))
        lin = pose.inverse().rotate(d_world)
        rel = prev.inverse().compose(pose)
        qx, qy, qz, qw = rel.quat
        angle = 2.0 * math.atan2(math.sqrt(qx * qx + qy * qy + qz * qz), qw)
        norm = math.sqrt(qx * qx + qy * qy + qz * qz)
        ang = (0.0, 0.0, 0.0) if norm < 1e-12 else tuple(angle * c / norm / dt for c in (qx, qy, qz))
        if self.p.dimensions == 2:
            lin, ang = (lin[0], lin[1], 0.0), (0.0, 0.0, ang[2])
        self._lin.append(lin)  # type: ignore[arg-type]
        self._ang.append(ang)  # type: ignore[arg-type]
        mean_lin = [sum(v[i] for v in self._lin) / len(self._lin) for i in range(3)]
        mean_ang = [sum(v[i] for v in self._ang) / len(self._ang) for i in range(3)]
        if self.p.noise_std > 0.0:
            mean_lin = [v + float(self.rng.normal(0.0, self.p.noise_std)) for v in mean_lin]
            mean_ang = [v + float(self.rng.normal(0.0, self.p.noise_std)) for v in mean_ang]
            if self.p.dimensions == 2:
                mean_lin[2] = mean_ang[0] = mean_ang[1] = 0.0
        x, y, z = pose.xyz
        qx, qy, qz, qw = pose.quat
        return {
            "header": gz.header(sim_time_ns, self.p.odom_frame, self.p.robot_base_frame),
            "pose": {"position": {"x": x, "y": y, "z": z}, "orientation": {"x": qx, "y": qy, "z": qz, "w": qw}},
            "twist": {
                "linear": dict(zip("xyz", mean_lin, strict=True)),
                "angular": dict(zip("xyz", mean_ang, strict=True)),
            },
        }

    def with_covariance(self, msg: dict) -> dict:
        """The OdometryWithCovariance gz-sim 8 sends beside `msg`: the same header, pose and twist, and 6×6
        covariances whose diagonal is the noise's variance (pose and twist alike), zeros elsewhere."""
        variance = self.p.noise_std * self.p.noise_std
        covariance = {"data": [variance if i % 7 == 0 else 0.0 for i in range(36)]}
        return {
            "header": msg["header"],
            "pose_with_covariance": {"pose": msg["pose"], "covariance": covariance},
            "twist_with_covariance": {"twist": msg["twist"], "covariance": covariance},
        }

    def _publish(self, sim_time_ns: int) -> None:
        msg = self.message(sim_time_ns)
        if msg is None:
            return
        self.last_message = msg
        if self._odom_pub is not None and self._odom_pub.matched:
            self._odom_pub.publish(msg)
        if self._cov_pub is not None and self._cov_pub.matched:
            self._cov_pub.publish(self.with_covariance(msg))
        if self._tf_pub is not None and self._tf_pub.matched:
            pose = dict(msg["pose"], name=self.p.robot_base_frame, header=msg["header"])
            self._tf_pub.publish({"header": gz.header(sim_time_ns), "pose": [pose]})

    def reset(self) -> None:
        self._last = None
        self.last_message = None
        self._lin.clear()
        self._ang.clear()

    def close(self) -> None:
        self.ctx.stepper.remove_task(self._task)
        t = self.ctx.transport
        if t is not None:
            for pub in (self._odom_pub, self._cov_pub, self._tf_pub):
                if pub is not None:
                    t.release(pub)
