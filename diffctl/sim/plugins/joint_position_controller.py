"""Gazebo's JointPositionController system (`gz-sim-joint-position-controller-system`).

SDF parameters as gz-sim 8 reads them: `joint_name` (repeatable; every joint gets the same command),
`joint_index` (0; these joints have one axis), PID `p_gain` (1), `i_gain` (0.1), `d_gain` (0.01), `i_max` (1),
`i_min` (-1), `cmd_max` (1000), `cmd_min` (-1000), `cmd_offset` (0), `initial_position` (0),
`use_velocity_commands` (false), `use_actuator_msg` + `actuator_number`, `topic`, `sub_topic`.
Target positions arrive as gz.msgs.Double on `topic`, else /model/<model>/<sub_topic>, else (with actuator
messages) gz.msgs.Actuators on /actuators, else /model/<model>/joint/<first joint>/<joint_index>/cmd_pos. Every
step the PID turns the first joint's position error into an effort for each joint; with velocity commands the
joints are instead driven to reach the target in one step, at most at cmd_max (when it is set).
"""

from __future__ import annotations

from typing import Any

from diffctl.description.model import Plugin
from diffctl.sim.entity import Entity
from diffctl.sim.plugins.base import PluginContext, SystemPlugin, bool_param, float_param
from diffctl.sim.plugins.gz_pid import GzPid
from diffctl.sim.plugins.system_support import find_joints, int_param, valid_topic


def command_topic(plugin: Plugin, model: str, default: str, use_actuator_msg: bool) -> str:
    """gz-sim's precedence for a joint controller's command topic: topic, sub_topic, /actuators, default."""
    if plugin.get("topic"):
        return valid_topic(plugin.get("topic") or "")
    if plugin.get("sub_topic"):
        return valid_topic(f"/model/{model}/{plugin.get('sub_topic')}")
    return "/actuators" if use_actuator_msg else valid_topic(default)


PID_TAGS = ("p_gain", "i_gain", "d_gain", "i_max", "i_min", "cmd_max", "cmd_min", "cmd_offset")


def pid_from(plugin: Plugin, source: str, defaults: dict[str, float], prefix: str = "") -> GzPid:
    def num(tag: str) -> float:
        value = float_param(plugin, prefix + tag, defaults[tag], source=source)
        return defaults[tag] if value is None else value

    return GzPid(*(num(tag) for tag in PID_TAGS))  # (GzPid's fields are in this order)


POSITION_PID = {
    "p_gain": 1.0,
    "i_gain": 0.1,
    "d_gain": 0.01,
    "i_max": 1.0,
    "i_min": -1.0,
    "cmd_max": 1000.0,
    "cmd_min": -1000.0,
    "cmd_offset": 0.0,
}


class JointPositionController(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, plugin: Plugin) -> None:
        self.ctx, self.entity = ctx, entity
        source = entity.model.source
        names = [n for n in plugin.get_all("joint_name") if n.strip()]
        self.joints = find_joints(ctx, entity, names, "JointPositionController")
        self.joint_index = int_param(plugin, "joint_index", 0, source=source)
        self.pid = pid_from(plugin, source, POSITION_PID)
        self.max_set = plugin.get("cmd_max") is not None
        self.velocity_mode = bool_param(plugin, "use_velocity_commands", False, source=source)
        self.initial = float_param(plugin, "initial_position", 0.0, source=source) or 0.0
        self.target = self.initial
        self.use_actuator_msg = bool_param(plugin, "use_actuator_msg", False, source=source) and bool(
            plugin.get("actuator_number")
        )
        self.actuator_number = int_param(plugin, "actuator_number", 0, source=source)
        self._dt_s = ctx.stepper.step_ns * 1e-9
        self._sub = None
        if not names:
            ctx.log.warn(f"JointPositionController on model {entity.name!r}: failed to get any <joint_name>")
            return
        default = f"/model/{entity.name}/joint/{names[0]}/{self.joint_index}/cmd_pos"
        self.topic = command_topic(plugin, entity.name, default, self.use_actuator_msg)
        if ctx.transport is not None:
            if self.use_actuator_msg:
                self._sub = ctx.transport.subscribe(self.topic, "gz.msgs.Actuators", self.on_actuators)
            else:
                self._sub = ctx.transport.subscribe(self.topic, "gz.msgs.Double", self.on_double)
        if self.joint_index != 0:
            ctx.log.warn(
                f"JointPositionController: <joint_index> {self.joint_index} but joint [{names[0]}] has only one "
                "axis: this controller is ignored"
            )
        elif self.joints:
            ctx.stepper.step_hooks.append(self._step)

    def on_double(self, fields: dict[str, Any]) -> None:
        self.command(float(fields.get("data", 0.0) or 0.0))

    def on_actuators(self, fields: dict[str, Any]) -> None:
        position = list(fields.get("position") if fields.get("position") is not None else [])
        if self.actuator_number < len(position):
            self.command(float(position[self.actuator_number]))

    def command(self, position: float) -> None:
        self.target = position  # a non-finite target makes the PID output 0, as gz-math's does

    def _step(self) -> None:
        ((pos, _vel, _e),) = self.entity.joint_states([self.joints[0]])
        error = pos - self.target
        if self.velocity_mode:
            limit = self.pid.cmd_max * self._dt_s
            if self.max_set and abs(error) > limit:
                velocity = self.pid.cmd_max if error < 0 else -self.pid.cmd_max
            else:
                velocity = -error / self._dt_s
            for h in self.joints:
                self.entity.set_joint_velocity(h, velocity)
            return
        for h in self.joints:  # (gz-sim updates its one PID once per joint)
            self.entity.add_joint_effort(h, self.pid.update(error, self._dt_s))

    def reset(self) -> None:
        self.pid.reset()
        self.target = self.initial

    def close(self) -> None:
        if self._step in self.ctx.stepper.step_hooks:
            self.ctx.stepper.step_hooks.remove(self._step)
        if self._sub is not None and self.ctx.transport is not None:
            self.ctx.transport.release(self._sub)
