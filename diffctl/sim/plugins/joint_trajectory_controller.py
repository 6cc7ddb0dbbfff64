"""Gazebo's JointTrajectoryController system (`gz-sim-joint-trajectory-controller-system`).

SDF parameters as gz-sim 8 reads them: `joint_name` (repeatable; default every single-axis joint of the model),
and, repeatable in joint order, `initial_position` and per joint a position and a velocity PID:
`position_p_gain`, `position_i_gain`, `position_d_gain`, `position_i_min`, `position_i_max`, `position_cmd_min`,
`position_cmd_max`, `position_cmd_offset` and the same with `velocity_` (every gain defaults to 0, i.e. off; the
limits to "no limit"); `topic` (/model/<model>/joint_trajectory); and `use_header_start_time`, which gz-sim reads
as an attribute of the <plugin> element. A gz.msgs.JointTrajectory replaces the current one; its points are
taken in turn as their time_from_start passes (from arrival, or the header's stamp), each setting the joints'
position, velocity and effort targets; the progress (reached points / points) goes out as gz.msgs.Float on
<topic>_progress. Every step each joint gets position PID + velocity PID + effort target as its effort.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from lxml import etree

from diffctl.bus import gz
from diffctl.description.model import Plugin
from diffctl.errors import DescriptionError
from diffctl.sim.entity import Entity, JointHandle
from diffctl.sim.plugins.base import PluginContext, SystemPlugin
from diffctl.sim.plugins.gz_pid import GzPid
from diffctl.sim.plugins.joint_command import PID_TAGS
from diffctl.sim.plugins.system_support import valid_topic

PID_DEFAULTS = {
    "p_gain": 0.0,
    "i_gain": 0.0,
    "d_gain": 0.0,
    "i_max": -1.0,
    "i_min": 0.0,
    "cmd_max": -1.0,
    "cmd_min": 0.0,
    "cmd_offset": 0.0,
}
SINGLE_AXIS = ("revolute", "continuous", "prismatic")


@dataclass
class _Joint:
    handle: JointHandle
    initial: float
    position_pid: GzPid
    velocity_pid: GzPid
    target: dict[str, float] = field(default_factory=dict)

    def reset_target(self) -> None:
        self.target = {"position": self.initial, "velocity": 0.0, "acceleration": 0.0, "effort": 0.0}


def _floats(plugin: Plugin, tag: str, source: str) -> list[float]:
    out = []
    for text in plugin.get_all(tag):
        try:
            out.append(float(text))
        except ValueError:
            raise DescriptionError(
                f"plugin {plugin.name!r}: <{tag}> {text!r} is not a number",
                source=source or None,
                field=f"plugin {plugin.filename}: {tag}",
            ) from None
    return out


def _header_start_time(plugin: Plugin) -> bool:
    if not plugin.xml:
        return False
    root = etree.fromstring(plugin.xml.encode())
    return (root.get("use_header_start_time") or "").strip().lower() in ("true", "1")


class JointTrajectoryController(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, plugin: Plugin) -> None:
        self.ctx, self.entity = ctx, entity
        source = entity.model.source
        names = plugin.get_all("joint_name") or [
            j.name for j in entity.model.joints if "::" not in j.name and j.type in SINGLE_AXIS
        ]
        handles = []
        for name in names:
            h = entity.joints.get(name)
            if h is None or h.joint.type not in SINGLE_AXIS:
                ctx.log.warn(f"JointTrajectoryController: model {entity.name!r} has no single-axis joint [{name}]")
            elif all(x.name != name for x in handles):
                handles.append(h)
        per_joint = {tag: _floats(plugin, tag, source) for tag in ("initial_position",)}
        for kind in ("position", "velocity"):
            for tag in PID_TAGS:
                per_joint[f"{kind}_{tag}"] = _floats(plugin, f"{kind}_{tag}", source)

        def nth(tag: str, i: int, default: float) -> float:
            values = per_joint[tag]
            return values[i] if i < len(values) else default

        self.joints: dict[str, _Joint] = {}
        for i, h in enumerate(handles):
            pids = [GzPid(*(nth(f"{k}_{t}", i, PID_DEFAULTS[t]) for t in PID_TAGS)) for k in ("position", "velocity")]
            joint = _Joint(h, nth("initial_position", i, 0.0), *pids)
            joint.reset_target()
            self.joints[h.name] = joint
        self.use_header_start_time = _header_start_time(plugin)
        self.topic = valid_topic(plugin.get("topic") or f"/model/{entity.name}/joint_trajectory")
        self.progress_topic = self.topic + "_progress"
        self._reset_trajectory()
        self._start_ns = 0
        self._dt_s = ctx.stepper.step_ns * 1e-9
        self._sub = self._progress = None
        if not self.joints:
            ctx.log.warn(f"JointTrajectoryController on model {entity.name!r} has no supported joints")
            return
        if ctx.transport is not None:
            self._sub = ctx.transport.subscribe(self.topic, "gz.msgs.JointTrajectory", self.on_trajectory)
            self._progress = ctx.transport.publisher(self.progress_topic, "gz.msgs.Float")
        ctx.stepper.step_hooks.append(self._step)

    def _reset_trajectory(self) -> None:
        self.status = "reached"  # no trajectory yet: nothing to warn about when the first arrives
        self.point_index = 0
        self.joint_names: list[str] = []
        self.points: list[dict[str, Any]] = []

    def on_trajectory(self, fields: dict[str, Any]) -> None:
        names = [str(n) for n in fields.get("joint_names") or []]
        if not names:
            self.ctx.log.warn("JointTrajectoryController: JointTrajectory message does not contain any joint names")
            return
        points = list(fields.get("points") or [])
        if self.status != "reached":
            self.ctx.log.warn(
                "JointTrajectoryController: a new JointTrajectory message was received while executing a previous "
                "trajectory"
            )
        stamp = (fields.get("header") or {}).get("stamp")
        self._start_ns = gz.stamp_ns(fields["header"]) if self.use_header_start_time and stamp else 0
        self.status, self.point_index, self.joint_names, self.points = "new", 0, names, points

    @staticmethod
    def _time_ns(point: dict[str, Any]) -> int:
        t = point.get("time_from_start") or {}
        return int(t.get("sec", 0) or 0) * 1_000_000_000 + int(t.get("nsec", 0) or 0)

    def _goal_reached(self) -> bool:
        return self.point_index + 1 >= len(self.points)

    def _step(self) -> None:
        now = self.ctx.stepper.sim_time_ns
        update = False
        if self.status == "new":
            if self._start_ns == 0:
                self._start_ns, self.status = now, "active"
            if not self.points:
                self.status = "reached"
            update = True
        if self.status == "active":
            elapsed = now - self._start_ns
            while not self._goal_reached() and self._time_ns(self.points[self.point_index]) < elapsed:
                self.point_index += 1
                update = True
        if update and self.status != "reached":
            point = self.points[self.point_index]
            for i, name in enumerate(self.joint_names):
                joint = self.joints.get(name)
                if joint is None:
                    continue
                for key, msg_key in (
                    ("position", "positions"),
                    ("velocity", "velocities"),
                    ("acceleration", "accelerations"),
                    ("effort", "effort"),
                ):
                    values = point.get(msg_key)
                    if values is not None and i < len(values) and math.isfinite(float(values[i])):
                        joint.target[key] = float(values[i])
            if self._goal_reached():
                self.status = "reached"
            if self._progress is not None and self._progress.matched:
                progress = (self.point_index + 1) / len(self.points)
                self._progress.publish({"header": gz.header(now), "data": progress})
        handles = [j.handle for j in self.joints.values()]
        for joint, (pos, vel, _e) in zip(self.joints.values(), self.entity.joint_states(handles), strict=True):
            effort = (
                joint.position_pid.update(pos - joint.target["position"], self._dt_s)
                + joint.velocity_pid.update(vel - joint.target["velocity"], self._dt_s)
                + joint.target["effort"]
            )
            self.entity.add_joint_effort(joint.handle, effort)

    def reset(self) -> None:
        for joint in self.joints.values():
            joint.reset_target()
            joint.position_pid.reset()
            joint.velocity_pid.reset()
        self._reset_trajectory()

    def close(self) -> None:
        if self._step in self.ctx.stepper.step_hooks:
            self.ctx.stepper.step_hooks.remove(self._step)
        t = self.ctx.transport
        if t is not None:
            for obj in (self._sub, self._progress):
                if obj is not None:
                    t.release(obj)
