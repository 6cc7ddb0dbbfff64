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
from diffctl.sim.plugins.joint_command import CONTROLLER_PID, CommandedJoints, double_value, pid_from


class JointController(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, plugin: Plugin) -> None:
        self.ctx, self.entity = ctx, entity
        source = entity.model.source
        self.commanded = CommandedJoints(ctx, entity, plugin, "JointController")
        self.joints = self.commanded.joints
        self.initial = float_param(plugin, "initial_velocity", 0.0, source=source) or 0.0
        self.target = self.initial
        self.force_mode = bool_param(plugin, "use_force_commands", False, source=source)
        self.pid = pid_from(plugin, source, CONTROLLER_PID)
        self._dt_s = ctx.stepper.step_ns * 1e-9
        self._sent: float | None = None
        self.topic = self.commanded.listen("cmd_vel", "velocity", self.command)
        if self.topic is not None and self.joints:
            self.commanded.attached.each_step(self._step)

    def on_double(self, fields: dict[str, Any]) -> None:
        self.command(double_value(fields))

    def command(self, velocity: float) -> None:
        self.target = velocity

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
        self.commanded.close()
