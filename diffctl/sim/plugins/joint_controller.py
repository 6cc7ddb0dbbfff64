"""Gazebo's JointController system (`gz-sim-joint-controller-system`): joint velocity commands.

SDF parameters as gz-sim 8 reads them: `joint_name` (repeatable), `initial_velocity` (0), `use_force_commands`
(false; then a PID on the velocity error gives efforts: `p_gain` 1, `i_gain` 0, `d_gain` 0, `i_max` 1,
`i_min` -1, `cmd_max` 1000, `cmd_min` -1000, `cmd_offset` 0), `use_actuator_msg` + `actuator_number`, `topic`,
`sub_topic`. Velocities arrive as gz.msgs.Double on `topic`, else /model/<model>/<sub_topic>, else (actuator
messages) the velocity of gz.msgs.Actuators on /actuators, else /model/<model>/joint/<first joint>/cmd_vel.
"""

from __future__ import annotations

from typing import Any

from diffctl.description.model import Plugin
from diffctl.sim.entity import Entity
from diffctl.sim.plugins.base import PluginContext, SystemPlugin, bool_param, float_param
from diffctl.sim.plugins.joint_position_controller import command_topic, pid_from
from diffctl.sim.plugins.system_support import find_joints, int_param

VELOCITY_PID = {
    "p_gain": 1.0,
    "i_gain": 0.0,
    "d_gain": 0.0,
    "i_max": 1.0,
    "i_min": -1.0,
    "cmd_max": 1000.0,
    "cmd_min": -1000.0,
    "cmd_offset": 0.0,
}


class JointController(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, plugin: Plugin) -> None:
        self.ctx, self.entity = ctx, entity
        source = entity.model.source
        names = [n for n in plugin.get_all("joint_name") if n.strip()]
        self.joints = find_joints(ctx, entity, names, "JointController")
        self.initial = float_param(plugin, "initial_velocity", 0.0, source=source) or 0.0
        self.target = self.initial
        self.force_mode = bool_param(plugin, "use_force_commands", False, source=source)
        self.pid = pid_from(plugin, source, VELOCITY_PID)
        self.use_actuator_msg = bool_param(plugin, "use_actuator_msg", False, source=source) and bool(
            plugin.get("actuator_number")
        )
        self.actuator_number = int_param(plugin, "actuator_number", 0, source=source)
        self._dt_s = ctx.stepper.step_ns * 1e-9
        self._sent: float | None = None
        self._sub = None
        if not names:
            ctx.log.warn(f"JointController on model {entity.name!r}: failed to get any <joint_name>")
            return
        default = f"/model/{entity.name}/joint/{names[0]}/cmd_vel"
        self.topic = command_topic(plugin, entity.name, default, self.use_actuator_msg)
        if ctx.transport is not None:
            if self.use_actuator_msg:
                self._sub = ctx.transport.subscribe(self.topic, "gz.msgs.Actuators", self.on_actuators)
            else:
                self._sub = ctx.transport.subscribe(self.topic, "gz.msgs.Double", self.on_double)
        if self.joints:
            ctx.stepper.step_hooks.append(self._step)

    def on_double(self, fields: dict[str, Any]) -> None:
        self.target = float(fields.get("data", 0.0) or 0.0)

    def on_actuators(self, fields: dict[str, Any]) -> None:
        velocity = list(fields.get("velocity") if fields.get("velocity") is not None else [])
        if self.actuator_number < len(velocity):
            self.target = float(velocity[self.actuator_number])

    def _step(self) -> None:
        if not self.force_mode:
            if self.target != self._sent:  # a velocity command holds in the physics until changed
                self._sent = self.target
                for h in self.joints:
                    self.entity.set_joint_velocity(h, self.target)
            return
        ((_pos, vel, _e),) = self.entity.joint_states([self.joints[0]])
        for h in self.joints:
            self.entity.add_joint_effort(h, self.pid.update(vel - self.target, self._dt_s))

    def reset(self) -> None:
        self.pid.reset()
        self.target = self.initial
        self._sent = None

    def close(self) -> None:
        if self._step in self.ctx.stepper.step_hooks:
            self.ctx.stepper.step_hooks.remove(self._step)
        if self._sub is not None and self.ctx.transport is not None:
            self.ctx.transport.release(self._sub)
