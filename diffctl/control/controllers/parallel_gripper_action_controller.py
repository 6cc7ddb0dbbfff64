"""parallel_gripper_action_controller/GripperActionController (Jazzy): a control_msgs/action/ParallelGripperCommand
server on `~/gripper_cmd` for one `joint`.

Claims `<joint>/position` and, when named, the `max_effort_interface` and `max_velocity_interface` commands, and the
joint's `state_interfaces` (position and velocity). A goal gives one position (another count is rejected) and,
where the interfaces exist, an effort and a velocity (else `max_effort` / `max_velocity`); every update writes
them. Success within `goal_tolerance`, stall detection and cancel as the gripper_controllers (gripper_monitor.py).
"""

from __future__ import annotations

from typing import Any

from diffctl.client.action.server import GoalResponse
from diffctl.control.controller_interface import CallbackReturn, InterfaceConfiguration, ReturnType
from diffctl.control.controllers.gripper_action_controller import GripperActionBase
from diffctl.control.controllers.gripper_monitor import StallMonitor
from diffctl.control.controllers.param_decl import Check, ParamDecl, table

PARALLEL_GRIPPER_COMMAND = "control_msgs/action/ParallelGripperCommand"
_GE0 = (Check("gt_eq", (0.0,)),)

DECLS = table([
    ParamDecl("action_monitor_rate", "double", 20.0, "Hz", True, (Check("gt_eq", (0.1,)),)),
    ParamDecl("joint", "string", "", read_only=True, checks=(Check("not_empty", ()),)),
    ParamDecl("state_interfaces", "string_array", ["position", "velocity"]),
    ParamDecl("goal_tolerance", "double", 0.01, checks=_GE0),
    ParamDecl("allow_stalling", "bool", False, "Allow stalling will make the action server return success if the "
              "gripper stalls when moving to the goal"),
    ParamDecl("stall_velocity_threshold", "double", 0.001, "stall velocity threshold"),
    ParamDecl("stall_timeout", "double", 1.0, "stall timeout", checks=_GE0),
    ParamDecl("max_effort_interface", "string", "", "Controller will claim the specified effort interface, e.g. "
              "robotiq_85_left_knuckle_joint/max_effort_interface."),
    ParamDecl("max_effort", "double", 10.0, "Default effort used for grasping (Newtons)", checks=_GE0),
    ParamDecl("max_velocity_interface", "string", "", "Controller will claim the speed specified interface, e.g. "
              "robotiq_85_left_knuckle_joint/max_velocity_interface."),
    ParamDecl("max_velocity", "double", 0.1, "Default target velocity used for grasping (meters/second)",
              checks=_GE0),
])  # fmt: skip


class GripperActionController(GripperActionBase):
    ACTION = PARALLEL_GRIPPER_COMMAND
    DECLS = DECLS

    def command_interface_configuration(self) -> InterfaceConfiguration:
        v = self.values
        names = [f"{v['joint']}/position"]
        names += [n for n in (v["max_effort_interface"], v["max_velocity_interface"]) if n]
        return InterfaceConfiguration.individual(names)

    def state_interface_configuration(self) -> InterfaceConfiguration:
        v = self.values
        return InterfaceConfiguration.individual([f"{v['joint']}/{k}" for k in v["state_interfaces"]])

    def on_configure(self, previous_state: Any) -> CallbackReturn:
        result = super().on_configure(previous_state)
        if result is CallbackReturn.SUCCESS:
            self.get_node().get_logger().info(f"Joint name is : {self.values['joint']}")
        return result

    def on_activate(self, previous_state: Any) -> CallbackReturn:
        v = self.values
        log = self.get_node().get_logger()
        self._cmd = self._find(self.command_interfaces, "position", "command")
        self._pos = self._find(self.state_interfaces, "position", "state")
        self._vel = self._find(self.state_interfaces, "velocity", "state")
        if self._cmd is None or self._pos is None or self._vel is None:
            return CallbackReturn.ERROR
        by_name = {c.name: c for c in self.command_interfaces}
        self._effort = by_name.get(v["max_effort_interface"]) if v["max_effort_interface"] else None
        self._speed = by_name.get(v["max_velocity_interface"]) if v["max_velocity_interface"] else None
        if v["max_effort_interface"] and self._effort is None:
            log.error(f"Expected max effort command interface `{v['max_effort_interface']}` not found")
            return CallbackReturn.FAILURE
        if v["max_velocity_interface"] and self._speed is None:
            log.error(f"Expected max velocity command interface `{v['max_velocity_interface']}` not found")
            return CallbackReturn.FAILURE
        self.monitor = StallMonitor(v["goal_tolerance"], v["stall_velocity_threshold"], v["stall_timeout"])
        self._command = self._hold_command()
        self._start_action_server()
        return CallbackReturn.SUCCESS

    def on_deactivate(self, previous_state: Any) -> None:
        self._cmd = self._pos = self._vel = self._effort = self._speed = None

    def _on_goal(self, goal: Any) -> GoalResponse:
        if len(goal.command.position) != 1:
            self.get_node().get_logger().error(
                f"Received action goal with wrong number of position values, expects 1, got "
                f"{len(goal.command.position)}")
            return GoalResponse.REJECT
        return super()._on_goal(goal)

    def _goal_command(self, goal: Any) -> tuple[float, ...]:
        v, command = self.values, goal.command
        speed = command.velocity[0] if v["max_velocity_interface"] and len(command.velocity) else v["max_velocity"]
        effort = command.effort[0] if v["max_effort_interface"] and len(command.effort) else v["max_effort"]
        return (float(command.position[0]), float(speed), float(effort))

    def _hold_command(self) -> tuple[float, ...]:
        return (self._pos.value, self.values["max_velocity"], self.values["max_effort"])

    def _result(self, position: float, effort: float, reached: bool) -> Any:
        result = self._action_types.Result(reached_goal=reached, stalled=not reached)
        result.state.position, result.state.effort = [position], [effort]
        return result

    def update(self, time: Any, period: Any) -> ReturnType:
        position, speed, effort = self._command
        now_ns = self.get_node().get_clock().now().nanoseconds
        self._conclude(now_ns, self._pos.value, self._vel.value, 0.0)  # upstream reports no computed effort
        self._cmd.value = position
        if self._speed is not None:
            self._speed.value = speed
        if self._effort is not None:
            self._effort.value = effort
        return ReturnType.OK
