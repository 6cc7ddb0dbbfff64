"""Gazebo's DiffDrive system (`gz-sim-diff-drive-system`): gz.msgs.Twist in, wheel speeds, odometry out.

SDF parameters as gz-sim reads them: `left_joint`/`right_joint` (repeatable), `wheel_separation` (1.0),
`wheel_radius` (0.2), `topic` (/model/<model>/cmd_vel), `odom_topic` (/model/<model>/odometry), `tf_topic`
(/model/<model>/tf), `frame_id` (<model>/odom), `child_frame_id` (<model>/<canonical link>),
`odom_publish_frequency` (50 Hz), and limits `[min|max]_[linear|angular]_[velocity|acceleration|jerk]`
(plus the older `[min|max]_[velocity|acceleration|jerk]` for the linear axis); a missing min is -max.
A command holds until the next one (no timeout), as in Gazebo. Non-finite commands are dropped.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from diffctl.bus import gz
from diffctl.description.model import Plugin
from diffctl.errors import DescriptionError
from diffctl.sim.entity import Entity, JointHandle
from diffctl.sim.plugins.base import PluginContext, SystemPlugin, float_param, rate_period_ns
from diffctl.sim.plugins.diff_drive_math import Limits, Odometry, limit_speed, wheel_speeds_rad_s


@dataclass(frozen=True)
class DiffDriveParams:
    left_joints: tuple[str, ...]
    right_joints: tuple[str, ...]
    wheel_separation_m: float
    wheel_radius_m: float
    topic: str
    odom_topic: str
    tf_topic: str
    frame_id: str
    child_frame_id: str
    odom_publish_frequency_hz: float
    linear: Limits
    angular: Limits

    @staticmethod
    def from_plugin(plugin: Plugin, model_name: str, canonical_link: str, source: str = "") -> DiffDriveParams:
        left, right = tuple(plugin.get_all("left_joint")), tuple(plugin.get_all("right_joint"))
        if not left or not right:
            raise DescriptionError(
                f"plugin {plugin.name!r} needs at least one <left_joint> and one <right_joint>",
                source=source or None,
                field=f"plugin {plugin.filename}",
            )

        def num(tag: str, default: float | None, positive: bool = False) -> float | None:
            return float_param(plugin, tag, default, source=source, positive=positive)

        def limits(axis: str, legacy: bool) -> Limits:
            vals: dict[str, float | None] = {}
            for kind in ("velocity", "acceleration", "jerk"):
                hi = num(f"max_{axis}_{kind}", num(f"max_{kind}", None) if legacy else None)
                lo = num(f"min_{axis}_{kind}", num(f"min_{kind}", None) if legacy else None)
                vals[f"max_{kind}"] = hi
                vals[f"min_{kind}"] = lo if lo is not None else (-hi if hi is not None else None)
            return Limits(**vals)

        base = f"/model/{model_name}"
        return DiffDriveParams(
            left_joints=left,
            right_joints=right,
            wheel_separation_m=num("wheel_separation", 1.0, positive=True) or 1.0,
            wheel_radius_m=num("wheel_radius", 0.2, positive=True) or 0.2,
            topic=plugin.get("topic") or f"{base}/cmd_vel",
            odom_topic=plugin.get("odom_topic") or f"{base}/odometry",
            tf_topic=plugin.get("tf_topic") or f"{base}/tf",
            frame_id=plugin.get("frame_id") or f"{model_name}/odom",
            child_frame_id=plugin.get("child_frame_id") or f"{model_name}/{canonical_link}",
            odom_publish_frequency_hz=num("odom_publish_frequency", 50.0, positive=True) or 50.0,
            linear=limits("linear", legacy=True),
            angular=limits("angular", legacy=False),
        )


class DiffDrive(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, params: DiffDriveParams) -> None:
        self.ctx, self.entity, self.p = ctx, entity, params
        self.left: list[JointHandle] = [entity.joint(n) for n in params.left_joints]
        self.right: list[JointHandle] = [entity.joint(n) for n in params.right_joints]
        self.odom = Odometry(params.wheel_separation_m, params.wheel_radius_m)
        self.target = (0.0, 0.0)  # commanded (linear, angular)
        # Last two limited commands per axis, newest first, for the speed limiter.
        self._lin = [0.0, 0.0]
        self._ang = [0.0, 0.0]
        self._hooked = False
        self._dt_s = ctx.stepper.step_ns * 1e-9
        self._apply(0.0, 0.0)
        self._task = ctx.stepper.add_task(
            f"diff_drive:{entity.name}",
            rate_period_ns(params.odom_publish_frequency_hz, ctx.stepper.step_ns),
            self._publish_odometry,
        )
        self._odom_pub = self._tf_pub = None
        self._sub = None
        t = ctx.transport
        if t is not None:
            self._odom_pub = t.publisher(params.odom_topic, "gz.msgs.Odometry")
            self._tf_pub = t.publisher(params.tf_topic, "gz.msgs.Pose_V")
            self._sub = t.subscribe(params.topic, "gz.msgs.Twist", self.on_twist)

    # --- commands ------------------------------------------------------------------------------------

    def on_twist(self, fields: dict[str, Any]) -> None:
        lin = float((fields.get("linear") or {}).get("x", 0.0) or 0.0)
        ang = float((fields.get("angular") or {}).get("z", 0.0) or 0.0)
        self.command(lin, ang)

    def command(self, linear_m_s: float, angular_rad_s: float) -> None:
        """A body twist to follow from the next step on (limited as the SDF says)."""
        if not (math.isfinite(linear_m_s) and math.isfinite(angular_rad_s)):
            self.ctx.log.throttled(f"nan:{self.entity.name}", f"{self.entity.name}: dropped a non-finite cmd_vel")
            return
        self.target = (linear_m_s, angular_rad_s)
        if self.p.linear.rate_limited or self.p.angular.rate_limited:
            if not self._hooked:
                self.ctx.stepper.step_hooks.append(self._limit_step)
                self._hooked = True
        else:
            self._push(
                limit_speed(linear_m_s, self._lin[0], self._lin[1], 0.0, self.p.linear),
                limit_speed(angular_rad_s, self._ang[0], self._ang[1], 0.0, self.p.angular),
            )

    def _limit_step(self) -> None:
        lin = limit_speed(self.target[0], self._lin[0], self._lin[1], self._dt_s, self.p.linear)
        ang = limit_speed(self.target[1], self._ang[0], self._ang[1], self._dt_s, self.p.angular)
        self._push(lin, ang)
        if lin == self._lin[1] == self.target[0] and ang == self._ang[1] == self.target[1]:
            # Settled on the target: no more per-step work until the next command.
            self.ctx.stepper.step_hooks.remove(self._limit_step)
            self._hooked = False

    def _push(self, lin: float, ang: float) -> None:
        changed = lin != self._lin[0] or ang != self._ang[0]
        self._lin = [lin, self._lin[0]]
        self._ang = [ang, self._ang[0]]
        if changed:
            self._apply(lin, ang)

    def _apply(self, lin: float, ang: float) -> None:
        wl, wr = wheel_speeds_rad_s(lin, ang, self.p.wheel_separation_m, self.p.wheel_radius_m)
        for h in self.left:
            self.entity.set_joint_velocity(h, wl)
        for h in self.right:
            self.entity.set_joint_velocity(h, wr)

    # --- odometry ------------------------------------------------------------------------------------

    def _publish_odometry(self, sim_time_ns: int) -> None:
        states = self.entity.joint_states([self.left[0], self.right[0]])
        self.odom.update(states[0][0], states[1][0], sim_time_ns * 1e-9)
        odom_pub, tf_pub = self._odom_pub, self._tf_pub
        if not ((odom_pub and odom_pub.matched) or (tf_pub and tf_pub.matched)):
            return
        o = self.odom
        half = o.heading_rad / 2.0
        position = {"x": o.x_m, "y": o.y_m, "z": 0.0}
        orientation = {"x": 0.0, "y": 0.0, "z": math.sin(half), "w": math.cos(half)}
        if odom_pub and odom_pub.matched:
            odom_pub.publish(
                {
                    "header": gz.header(sim_time_ns, self.p.frame_id, self.p.child_frame_id),
                    "pose": {"position": position, "orientation": orientation},
                    "twist": {
                        "linear": {"x": o.linear_m_s, "y": 0.0, "z": 0.0},
                        "angular": {"x": 0.0, "y": 0.0, "z": o.angular_rad_s},
                    },
                }
            )
        if tf_pub and tf_pub.matched:
            h = gz.header(sim_time_ns, self.p.frame_id, self.p.child_frame_id)
            tf_pub.publish(
                {
                    "header": gz.header(sim_time_ns),
                    "pose": [
                        {"name": self.p.child_frame_id, "header": h, "position": position, "orientation": orientation}
                    ],
                }
            )

    def reset(self) -> None:
        self.odom.reset()
        self.target = (0.0, 0.0)
        self._lin = [0.0, 0.0]
        self._ang = [0.0, 0.0]
        self._apply(0.0, 0.0)

    def close(self) -> None:
        self.ctx.stepper.remove_task(self._task)
        if self._hooked:
            self.ctx.stepper.step_hooks.remove(self._limit_step)
            self._hooked = False
        t = self.ctx.transport
        if t is not None:
            for obj in (self._sub, self._odom_pub, self._tf_pub):
                if obj is not None:
                    t.release(obj)
