"""Gazebo's MecanumDrive system (`gz-sim-mecanum-drive-system`): gz.msgs.Twist in, four wheel speeds, odometry out.

SDF parameters as gz-sim 8 reads them: `front_left_joint`, `front_right_joint`, `back_left_joint`,
`back_right_joint` (each repeatable), `wheel_separation` (1.0), `wheelbase` (1.0), `wheel_radius` (0.2),
`odom_publish_frequency` (50 Hz), `topic` (/model/<model>/cmd_vel), `odom_topic` (/model/<model>/odometry),
`tf_topic` (/model/<model>/tf), `frame_id` (<model>/odom), `child_frame_id` (<model>/<canonical link>), and the
speed limiter's `[min|max]_[velocity|acceleration|jerk]`, which bound the linear and lateral speeds and, with the
same numbers, the angular one. The twist's linear.x, linear.y and angular.z are followed until the next command.
A wheel moves a mecanum robot sideways only through its rollers: in SDF, a collision whose `<fdir1>` friction
direction has `<mu2>` 0 (see sim/mecanum_rollers.py).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from diffctl.description.model import Plugin
from diffctl.sim.entity import Entity, JointHandle
from diffctl.sim.plugins.attachments import Attachments
from diffctl.sim.plugins.base import PluginContext, SystemPlugin, float_param, rate_period_ns
from diffctl.sim.plugins.diff_drive_math import Limits, limit_speed
from diffctl.sim.plugins.steering_math import MecanumOdometry, mecanum_wheel_speeds
from diffctl.sim.plugins.system_support import (
    OdometryNames,
    OdometryOutput,
    find_joints,
    finite_or_none,
    planar_twist,
    speed_limits,
    valid_topic,
)

WHEELS = ("front_left_joint", "front_right_joint", "back_left_joint", "back_right_joint")


@dataclass(frozen=True)
class MecanumDriveParams:
    joints: tuple[tuple[str, ...], ...]  # per wheel position, in WHEELS order
    wheel_separation_m: float
    wheelbase_m: float
    wheel_radius_m: float
    odom_publish_frequency_hz: float
    topic: str
    odometry: OdometryNames
    limits: Limits

    @staticmethod
    def from_plugin(plugin: Plugin, model: str, canonical_link: str, source: str = "") -> MecanumDriveParams:
        def num(tag: str, default: float | None) -> float | None:
            return float_param(plugin, tag, default, source=source)

        return MecanumDriveParams(
            joints=tuple(tuple(plugin.get_all(tag)) for tag in WHEELS),
            wheel_separation_m=num("wheel_separation", 1.0) or 1.0,
            wheelbase_m=num("wheelbase", 1.0) or 1.0,
            wheel_radius_m=num("wheel_radius", 0.2) or 0.2,
            odom_publish_frequency_hz=num("odom_publish_frequency", 50.0) or 0.0,
            topic=valid_topic(plugin.get("topic") or f"/model/{model}/cmd_vel"),
            odometry=OdometryNames.from_plugin(plugin, model, canonical_link, tf_topic_as_given=True),
            limits=speed_limits(plugin, source),
        )


class MecanumDrive(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, params: MecanumDriveParams) -> None:
        self.ctx, self.entity, self.p = ctx, entity, params
        self.wheels: list[list[JointHandle]] = [find_joints(ctx, entity, n, "MecanumDrive") for n in params.joints]
        self.active = all(self.wheels)
        if not self.active:
            ctx.log.warn(f"MecanumDrive on model {entity.name!r} needs a joint at each wheel: it will not drive")
        self.odom = MecanumOdometry(params.wheel_separation_m, params.wheelbase_m, params.wheel_radius_m)
        self.target = (0.0, 0.0, 0.0)
        self._last = [(0.0, 0.0, 0.0), (0.0, 0.0, 0.0)]  # the last two limited commands, newest first
        self._dt_s = ctx.stepper.step_ns * 1e-9
        self.attached = Attachments(ctx)
        self.attached.subscribe(params.topic, "gz.msgs.Twist", self.on_twist)
        self.output = OdometryOutput(self.attached, params.odometry)
        if self.active:
            self._apply((0.0, 0.0, 0.0))  # held until the first command, as gz-sim commands 0 every step
            self.attached.each_step(self._step)
            hz = params.odom_publish_frequency_hz
            period = rate_period_ns(hz, ctx.stepper.step_ns) if hz > 0 else ctx.stepper.step_ns
            self.attached.every(f"mecanum_drive:{entity.name}", period, self._odometry)

    def on_twist(self, fields: dict[str, Any]) -> None:
        self.command(*planar_twist(fields))

    def command(self, linear_m_s: float, lateral_m_s: float, angular_rad_s: float) -> None:
        if not finite_or_none(linear_m_s, lateral_m_s, angular_rad_s):
            self.ctx.log.throttled(f"nan:{self.entity.name}", f"{self.entity.name}: dropped a non-finite cmd_vel")
            return
        self.target = (linear_m_s, lateral_m_s, angular_rad_s)

    def _step(self) -> None:
        (v0, y0, w0), (v1, y1, w1) = self._last
        lim, dt = self.p.limits, self._dt_s
        cmd = (
            limit_speed(self.target[0], v0, v1, dt, lim),
            limit_speed(self.target[1], y0, y1, dt, lim),
            limit_speed(self.target[2], w0, w1, dt, lim),
        )
        if cmd == self._last[0] == self._last[1]:
            return  # settled: the wheels already turn at these speeds
        self._last = [cmd, self._last[0]]
        self._apply(cmd)

    def _apply(self, cmd: tuple[float, float, float]) -> None:
        speeds = mecanum_wheel_speeds(*cmd, self.p.wheel_separation_m, self.p.wheelbase_m, self.p.wheel_radius_m)
        for handles, speed in zip(self.wheels, speeds, strict=True):
            for h in handles:
                self.entity.set_joint_velocity(h, speed)

    def _odometry(self, sim_time_ns: int) -> None:
        t = sim_time_ns * 1e-9
        if not self.odom.initialized:
            self.odom.reset(t)
            return
        states = self.entity.joint_states([w[0] for w in self.wheels])
        self.odom.update(*(s[0] for s in states), t)
        o = self.odom
        self.output.publish(sim_time_ns, (o.x_m, o.y_m, o.heading_rad), (o.linear_m_s, o.lateral_m_s, o.angular_rad_s))

    def reset(self) -> None:
        self.odom.initialized = False
        self.target = (0.0, 0.0, 0.0)
        self._last = [(0.0, 0.0, 0.0), (0.0, 0.0, 0.0)]
        if self.active:
            self._apply((0.0, 0.0, 0.0))

    def close(self) -> None:
        self.attached.close()
