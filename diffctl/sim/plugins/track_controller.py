"""Gazebo's TrackController system (`gz-sim-track-controller-system`): a track link whose contacts move.

gz-sim drives a track by giving each contact of the track link's collisions a friction direction and a surface
velocity (gz-physics' contact surface motion), which PyBullet lacks; here the track's collisions ride on a belt
that the model's TrackBelts moves each step as those contacts would move the vehicle (track_belts.py,
track_math.py). This system keeps what gz-sim's keeps: the track's speed (limited), its centre of rotation, its
travelled distance.

SDF parameters as gz-sim 8 reads them: `link`, `velocity_topic` (/model/<m>/link/<link>/track_cmd_vel,
gz.msgs.Double), `center_of_rotation_topic` (…/track_cmd_center_of_rotation, gz.msgs.Vector3d: a point in the
world; not finite = none, the track pushes along itself), `track_orientation` (roll pitch yaw of the track's
frame in the link's; read when the model is built), `odometry_topic` (…/odometry: the track's travelled distance
and speed), `odometry_publish_frequency` (50 Hz), `max_command_age` (s; an older command stops the track),
`[min|max]_[velocity|acceleration|jerk]`.
"""

from __future__ import annotations

import math
from typing import Any

from diffctl.bus import gz
from diffctl.description.model import Plugin
from diffctl.sim.entity import DEFAULT_MAX_SPEED, Entity
from diffctl.sim.plugins.base import PluginContext, SystemPlugin, float_param, rate_period_ns
from diffctl.sim.plugins.diff_drive_math import limit_speed
from diffctl.sim.plugins.system_support import speed_limits, valid_topic
from diffctl.sim.plugins.track_math import Vec3


class TrackController(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, plugin: Plugin) -> None:
        self.ctx, self.entity = ctx, entity
        source = entity.model.source
        self.link = (plugin.get("link") or "").strip()
        prefix = f"/model/{entity.name}/link/{self.link}"
        self.velocity_topic = valid_topic(plugin.get("velocity_topic") or f"{prefix}/track_cmd_vel")
        self.cor_topic = valid_topic(plugin.get("center_of_rotation_topic") or f"{prefix}/track_cmd_center_of_rotation")
        self.odometry_topic = valid_topic(plugin.get("odometry_topic") or f"{prefix}/odometry")
        hz = float_param(plugin, "odometry_publish_frequency", 50.0, source=source) or 50.0
        age = float_param(plugin, "max_command_age", None, source=source)
        self.max_command_age_ns = round(age * 1e9) if age is not None else None
        self.limits = speed_limits(plugin, source)
        self.velocity = 0.0  # as commanded
        self.speed = 0.0  # as limited, this step
        self.center: Vec3 | None = None  # the centre of rotation, in the world
        self.position_m = 0.0
        self._last = [0.0, 0.0]
        self._command_ns = 0
        self._dt_s = ctx.stepper.step_ns * 1e-9
        self.belt = entity.belts.get(self.link)
        self._subs: list[Any] = []
        self._odom = None
        if self.belt is None:
            ctx.log.warn(f"TrackController: could not find track link [{self.link}] with collisions in {entity.name!r}")
            return
        t = ctx.transport
        if t is not None:
            self._subs.append(t.subscribe(self.velocity_topic, "gz.msgs.Double", self.on_velocity))
            self._subs.append(t.subscribe(self.cor_topic, "gz.msgs.Vector3d", self.on_center))
            self._odom = t.publisher(self.odometry_topic, "gz.msgs.Odometry")
        ctx.stepper.step_hooks.append(self._step)
        period = rate_period_ns(hz, ctx.stepper.step_ns)
        self._task = ctx.stepper.add_task(f"track:{entity.name}:{self.link}", period, self._publish)

    def on_velocity(self, fields: dict[str, Any]) -> None:
        self.command(float(fields.get("data", 0.0) or 0.0))

    def on_center(self, fields: dict[str, Any]) -> None:
        self.set_center(tuple(float(fields.get(k, 0.0) or 0.0) for k in "xyz"))  # type: ignore[arg-type]

    def command(self, velocity_m_s: float) -> None:
        if math.isfinite(velocity_m_s):
            self.velocity = velocity_m_s
            self._command_ns = self.ctx.stepper.sim_time_ns

    def set_center(self, point: Vec3 | None) -> None:
        """A new centre of rotation; one not finite (TrackedVehicle's for straight driving) is none."""
        self.center = point if point is not None and all(math.isfinite(v) for v in point) else None
        self._command_ns = self.ctx.stepper.sim_time_ns

    def _step(self) -> None:
        target = self.velocity
        age = self.max_command_age_ns
        if age is not None and self.ctx.stepper.sim_time_ns - self._command_ns > age:
            target = 0.0
        # (without a <max_velocity> still capped, as joint commands are: absurd speeds never reach the physics)
        target = max(-DEFAULT_MAX_SPEED, min(DEFAULT_MAX_SPEED, target))
        self.speed = limit_speed(target, self._last[0], self._last[1], self._dt_s, self.limits)
        self._last = [self.speed, self._last[0]]
        self.position_m += self.speed * self._dt_s

    def _publish(self, sim_time_ns: int) -> None:
        if self._odom is not None and self._odom.matched:
            self._odom.publish(
                {
                    "header": gz.header(sim_time_ns),
                    "pose": {"position": {"x": self.position_m, "y": 0.0, "z": 0.0}},
                    "twist": {"linear": {"x": self.speed, "y": 0.0, "z": 0.0}},
                }
            )

    def reset(self) -> None:
        self.velocity = self.speed = self.position_m = 0.0
        self.center = None
        self._last = [0.0, 0.0]

    def close(self) -> None:
        if self._step in self.ctx.stepper.step_hooks:
            self.ctx.stepper.step_hooks.remove(self._step)
            self.ctx.stepper.remove_task(self._task)
        t = self.ctx.transport
        if t is not None:
            for obj in (*self._subs, self._odom):
                if obj is not None:
                    t.release(obj)
