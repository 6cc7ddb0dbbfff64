"""Gazebo's AckermannSteering system (`gz-sim-ackermann-steering-system`): car-like steering and drive.

SDF parameters as gz-sim 8 reads them: `left_joint`/`right_joint` (driven wheels, repeatable),
`left_steering_joint`/`right_steering_joint` (repeatable), `wheel_separation` (1.0), `kingpin_width` (0.8),
`wheel_base` (1.0), `steering_limit` (0.5 rad), `wheel_radius` (0.2), `steer_p_gain` (1.0: the steering
joints turn at gain × angle error), `odom_publish_frequency` (50 Hz), `topic` or `sub_topic`
(/model/<model>/<sub_topic>), `odom_topic`, `tf_topic`, `frame_id`, `child_frame_id`, and the speed limiter's
`[min|max]_[velocity|acceleration|jerk]` (the same numbers bound the linear and the angular speed).
Default topics: gz.msgs.Twist on /model/<model>/cmd_vel, odometry on /model/<model>/odometry, tf on
/model/<model>/tf. With `steering_only` (or `use_actuator_msg`, which implies it) only the steering joints are
driven, to a mean angle from gz.msgs.Double on /model/<model>/steer_angle, or from gz.msgs.Actuators' position
`actuator_number` on /actuators; there is no odometry then.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from diffctl.description.model import Plugin
from diffctl.sim.entity import Entity
from diffctl.sim.plugins.attachments import Attachments
from diffctl.sim.plugins.base import PluginContext, SystemPlugin, bool_param, float_param, rate_period_ns
from diffctl.sim.plugins.diff_drive_math import Limits, limit_speed
from diffctl.sim.plugins.steering_math import AckermannOdometry, ackermann_command, ackermann_steer_only
from diffctl.sim.plugins.system_support import (
    OdometryNames,
    OdometryOutput,
    find_joints,
    finite_or_none,
    int_param,
    planar_twist,
    speed_limits,
    valid_topic,
)


@dataclass(frozen=True)
class AckermannSteeringParams:
    left_joints: tuple[str, ...]
    right_joints: tuple[str, ...]
    left_steering_joints: tuple[str, ...]
    right_steering_joints: tuple[str, ...]
    steering_only: bool
    use_actuator_msg: bool
    actuator_number: int
    wheel_separation_m: float
    kingpin_width_m: float
    wheel_base_m: float
    steering_limit_rad: float
    wheel_radius_m: float
    steer_p_gain: float
    odom_publish_frequency_hz: float
    topic: str
    odometry: OdometryNames
    limits: Limits

    @staticmethod
    def from_plugin(plugin: Plugin, model: str, canonical_link: str, source: str = "") -> AckermannSteeringParams:
        def num(tag: str, default: float) -> float:
            value = float_param(plugin, tag, default, source=source)
            return default if value is None else value

        steering_only = bool_param(plugin, "steering_only", False, source=source)
        actuator = bool_param(plugin, "use_actuator_msg", False, source=source) and plugin.get("actuator_number")
        steering_only = steering_only or bool(actuator)
        base = f"/model/{model}"
        if plugin.get("topic"):
            topic = plugin.get("topic") or ""
        elif plugin.get("sub_topic"):
            topic = f"{base}/{plugin.get('sub_topic')}"
        elif steering_only:
            topic = "/actuators" if actuator else f"{base}/steer_angle"
        else:
            topic = f"{base}/cmd_vel"
        return AckermannSteeringParams(
            left_joints=() if steering_only else tuple(plugin.get_all("left_joint")),
            right_joints=() if steering_only else tuple(plugin.get_all("right_joint")),
            left_steering_joints=tuple(plugin.get_all("left_steering_joint")),
            right_steering_joints=tuple(plugin.get_all("right_steering_joint")),
            steering_only=steering_only,
            use_actuator_msg=bool(actuator),
            actuator_number=int_param(plugin, "actuator_number", 0, source=source),
            wheel_separation_m=num("wheel_separation", 1.0),
            kingpin_width_m=0.8 if steering_only else num("kingpin_width", 0.8),
            wheel_base_m=num("wheel_base", 1.0),
            steering_limit_rad=num("steering_limit", 0.5),
            wheel_radius_m=0.2 if steering_only else num("wheel_radius", 0.2),
            steer_p_gain=num("steer_p_gain", 1.0),
            odom_publish_frequency_hz=num("odom_publish_frequency", 50.0),
            topic=valid_topic(topic),
            odometry=OdometryNames.from_plugin(plugin, model, canonical_link),
            limits=speed_limits(plugin, source),
        )


class AckermannSteering(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, params: AckermannSteeringParams) -> None:
        self.ctx, self.entity, self.p = ctx, entity, params
        name = "AckermannSteering"
        self.left = find_joints(ctx, entity, params.left_joints, name)
        self.right = find_joints(ctx, entity, params.right_joints, name)
        self.left_steer = find_joints(ctx, entity, params.left_steering_joints, name)
        self.right_steer = find_joints(ctx, entity, params.right_steering_joints, name)
        wheels = params.steering_only or (self.left and self.right)
        self.active = bool(self.left_steer and self.right_steer and wheels)
        if not self.active:
            ctx.log.warn(f"{name} on model {entity.name!r} is missing joints: it will not drive")
        self.odom = AckermannOdometry(params.wheel_base_m, params.wheel_radius_m)
        self.target = (0.0, 0.0)  # (linear, angular), or (steering angle, 0) when steering only
        self._last = [(0.0, 0.0), (0.0, 0.0)]
        self._dt_s = ctx.stepper.step_ns * 1e-9
        self._wheels: tuple[float, float] | None = None  # the wheel speeds last sent
        self.attached = Attachments(ctx)
        self.output: OdometryOutput | None = None
        if not params.steering_only:
            self.attached.subscribe(params.topic, "gz.msgs.Twist", self.on_twist)
            self.output = OdometryOutput(self.attached, params.odometry)
        elif params.use_actuator_msg:
            self.attached.subscribe(params.topic, "gz.msgs.Actuators", self.on_actuators)
        else:
            self.attached.subscribe(params.topic, "gz.msgs.Double", self.on_angle)
        if self.active:
            self.attached.each_step(self._step)
            if not params.steering_only:
                hz = params.odom_publish_frequency_hz
                period = rate_period_ns(hz, ctx.stepper.step_ns) if hz > 0 else ctx.stepper.step_ns
                self.attached.every(f"ackermann:{entity.name}", period, self._odometry)

    # --- commands ------------------------------------------------------------------------------------

    def on_twist(self, fields: dict[str, Any]) -> None:
        linear, _, angular = planar_twist(fields)
        self.command(linear, angular)

    def on_angle(self, fields: dict[str, Any]) -> None:
        self.command(float(fields.get("data", 0.0) or 0.0), 0.0)

    def on_actuators(self, fields: dict[str, Any]) -> None:
        position = list(fields.get("position") if fields.get("position") is not None else [])
        n = self.p.actuator_number
        if n >= len(position):
            self.ctx.log.throttled(
                f"act:{self.entity.name}",
                f"AckermannSteering: actuator_number {n} is past the {len(position)} positions of the message",
            )
            return
        self.command(float(position[n]), 0.0)

    def command(self, a: float, b: float) -> None:
        """A (linear m/s, angular rad/s) twist, or (steering angle rad, 0) in steering-only mode."""
        if not finite_or_none(a, b):
            self.ctx.log.throttled(f"nan:{self.entity.name}", f"{self.entity.name}: dropped a non-finite command")
            return
        self.target = (a, b)

    # --- every step ----------------------------------------------------------------------------------

    def _step(self) -> None:
        p, dt, lim = self.p, self._dt_s, self.p.limits
        (a0, b0), (a1, b1) = self._last
        if p.steering_only:
            angle = limit_speed(self.target[0], b0, b1, dt, lim)  # (gz limits the angle as an angular speed)
            if abs(angle) > p.steering_limit_rad:
                angle = p.steering_limit_rad if angle > 0 else -p.steering_limit_rad
            self._last = [(0.0, angle), self._last[0]]
            left, right = ackermann_steer_only(angle, p.wheel_base_m, p.wheel_separation_m)
        else:
            lin = limit_speed(self.target[0], a0, a1, dt, lim)
            ang = limit_speed(self.target[1], b0, b1, dt, lim)
            self._last = [(lin, ang), self._last[0]]
            geometry = (p.wheel_base_m, p.wheel_separation_m, p.kingpin_width_m, p.steering_limit_rad, p.wheel_radius_m)
            left, right, wl, wr = ackermann_command(lin, ang, *geometry)
            if (wl, wr) != self._wheels:
                self._wheels = (wl, wr)
                for h in self.left:
                    self.entity.set_joint_velocity(h, wl)
                for h in self.right:
                    self.entity.set_joint_velocity(h, wr)
        states = self.entity.joint_states([self.left_steer[0], self.right_steer[0]])
        sides = ((self.left_steer, left, states[0][0]), (self.right_steer, right, states[1][0]))
        for handles, target, pos in sides:
            for h in handles:
                self.entity.set_joint_velocity(h, p.steer_p_gain * (target - pos))

    def _odometry(self, sim_time_ns: int) -> None:
        wheels = self.entity.joint_states([self.left[0], self.right[0], self.left_steer[0], self.right_steer[0]])
        self.odom.update(*(s[0] for s in wheels), sim_time_ns * 1e-9)
        if self.output is not None:
            o = self.odom
            self.output.publish(sim_time_ns, (o.x_m, o.y_m, o.heading_rad), (o.linear_m_s, 0.0, o.angular_rad_s))

    def reset(self) -> None:
        self.odom.reset()
        self.target = (0.0, 0.0)
        self._last = [(0.0, 0.0), (0.0, 0.0)]
        self._wheels = None  # re-sent on the next step

    def close(self) -> None:
        self.attached.close()
