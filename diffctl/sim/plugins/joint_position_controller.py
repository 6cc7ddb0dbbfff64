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
from diffctl.sim.plugins.joint_command import CONTROLLER_PID, CommandedJoints, double_value, pid_from
from diffctl.sim.plugins.system_support import int_param

POSITION_PID = {**CONTROLLER_PID, "i_gain": 0.1, "d_gain": 0.01}


class JointPositionController(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, plugin: Plugin) -> None:
        self.ctx, self.entity = ctx, entity
        source = entity.model.source
        self.commanded = CommandedJoints(ctx, entity, plugin, "JointPositionController")
        self.joints = self.commanded.joints
        self.joint_index = int_param(plugin, "joint_index", 0, source=source)
        self.pid = pid_from(plugin, source, POSITION_PID)
        self.max_set = plugin.get("cmd_max") is not None
        self.velocity_mode = bool_param(plugin, "use_velocity_commands", False, source=source)
        self.initial = float_param(plugin, "initial_position", 0.0, source=source) or 0.0
        self.target = self.initial
        self._dt_s = ctx.stepper.step_ns * 1e-9
        self.topic = self.commanded.listen(f"{self.joint_index}/cmd_pos", "position", self.command)
        if self.topic is None:
            return
        if self.joint_index != 0:
            ctx.log.warn(
                f"JointPositionController: <joint_index> {self.joint_index} but joint [{self.commanded.names[0]}] "
                "has only one axis: this controller is ignored"
            )
        elif self.joints:
            self.commanded.attached.each_step(self._step)

    def on_double(self, fields: dict[str, Any]) -> None:
        self.command(double_value(fields))

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
        self.commanded.close()
