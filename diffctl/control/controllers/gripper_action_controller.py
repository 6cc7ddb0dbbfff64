"""position_controllers/GripperActionController and effort_controllers/GripperActionController (gripper_controllers,
Jazzy; deprecated upstream in favour of parallel_gripper_action_controller, with the same warning).

One `joint` driven to the position of a control_msgs/action/GripperCommand goal on `~/gripper_cmd` (the action
server exists while the controller is active). Claims `<joint>/position` or `<joint>/effort` and the joint's
position and velocity states. The position variant forwards the goal position; the effort variant turns the
position and velocity errors into an effort through a PID (`gains.<joint>.p/i/d/i_clamp`, declared when it
activates), clamped to ±max_effort of the goal. A goal succeeds within `goal_tolerance`, or stalls (gripper_monitor),
and a cancel holds the current position. The effort PID steps by the control period (upstream measures wall time
between updates, which would make the simulated gripper depend on the machine's speed). A goal preempted by another
is aborted (upstream marks it canceled, which its action server refuses for a goal nobody asked to cancel).
"""

from __future__ import annotations

import math
from typing import Any

from diffctl.client.action.server import ActionServer, CancelResponse, GoalResponse
from diffctl.client.interfaces import cls
from diffctl.control.controller_interface import (
    CallbackReturn,
    ControllerInterface,
    InterfaceConfiguration,
    ReturnType,
)
from diffctl.control.controllers.gripper_monitor import REACHED, StallMonitor
from diffctl.control.controllers.param_decl import Check, ParamDecl, declare_all, read_declared, table
from diffctl.control.controllers.realtime_goal import RealtimeGoal
from diffctl.control.math.pid import Pid, PidGains

GRIPPER_COMMAND = "control_msgs/action/GripperCommand"
_GE0 = (Check("gt_eq", (0.0,)),)

DECLS = table([
    ParamDecl("action_monitor_rate", "double", 20.0, "Hz", checks=(Check("gt_eq", (0.1,)),)),
    ParamDecl("joint", "string", ""),
    ParamDecl("goal_tolerance", "double", 0.01, checks=_GE0),
    ParamDecl("max_effort", "double", 0.0, "Max allowable effort", checks=_GE0),
    ParamDecl("allow_stalling", "bool", False, "Allow stalling will make the action server return success if the "
              "gripper stalls when moving to the goal"),
    ParamDecl("stall_velocity_threshold", "double", 0.001, "stall velocity threshold"),
    ParamDecl("stall_timeout", "double", 1.0, "stall timeout"),
])  # fmt: skip


class GripperActionBase(ControllerInterface):
    """What both gripper action controllers share: parameters, the action server, goals and their outcome."""

    ACTION = GRIPPER_COMMAND
    DECLS = DECLS

    def __init__(self) -> None:
        super().__init__()
        self._action_server: Any = None
        self._goal_timer: Any = None
        self._active_goal: RealtimeGoal | None = None
        self._command: tuple[float, ...] = ()

    def on_init(self) -> None:
        self.values = declare_all(self.get_node(), self.DECLS, self.get_name())

    def _read(self) -> dict[str, Any]:
        node = self.get_node()
        return read_declared(self.DECLS, {n: node.get_parameter(n).value for n in self.DECLS}, self.get_name())

    def on_configure(self, previous_state: Any) -> CallbackReturn:
        log = self.get_node().get_logger()
        self.values = v = self._read()
        log.info(f"Action status changes will be monitored at {v['action_monitor_rate']:f} Hz.")
        if not v["joint"]:
            log.error("Joint name cannot be empty")
            return CallbackReturn.ERROR
        return CallbackReturn.SUCCESS

    def _find(self, handles: list[Any], interface: str, kind: str) -> Any:
        """The claimed handle of `interface` for the joint, or None after logging upstream's complaint."""
        log = self.get_node().get_logger()
        handle = next((h for h in handles if h.get_interface_name() == interface), None)
        if handle is None:
            log.error(f"Expected 1 {interface} {kind} interface")
            return None
        if handle.get_prefix_name() != self.values["joint"]:
            log.error(f"{interface.capitalize()} {kind} interface is different than joint name "
                      f"`{handle.get_prefix_name()}` != `{self.values['joint']}`")
            return None
        return handle

    def _start_action_server(self) -> None:
        if self._action_server is not None:
            self._action_server.destroy()
        self._action_types = cls(self.ACTION)
        self._action_server = ActionServer(self.get_node(), self._action_types, "~/gripper_cmd",
                                           lambda gh: self._action_types.Result(), goal_callback=self._on_goal,
                                           handle_accepted_callback=self._on_accepted, cancel_callback=self._on_cancel)

    def _on_goal(self, goal: Any) -> GoalResponse:
        self.get_node().get_logger().info("Received & accepted new action goal")
        return GoalResponse.ACCEPT

    def _goal_command(self, goal: Any) -> tuple[float, ...]:
        raise NotImplementedError

    def _on_accepted(self, goal_handle: Any) -> None:
        goal = RealtimeGoal(goal_handle)
        previous = self._active_goal
        if previous is not None:
            previous.set_aborted(self._action_types.Result())
            previous.run_non_realtime()
        self._command = self._goal_command(goal_handle.request)
        self.monitor.start(self.get_node().get_clock().now().nanoseconds)
        goal_handle.execute(goal.execute)
        self._active_goal = goal
        node = self.get_node()
        if self._goal_timer is not None:
            node.destroy_timer(self._goal_timer)
        from diffctl.client.clock import Clock
        from diffctl.client.clock_type import ClockType

        self._goal_timer = node.create_timer(1.0 / self.values["action_monitor_rate"], goal.run_non_realtime,
                                             clock=Clock(clock_type=ClockType.STEADY_TIME))

    def _on_cancel(self, goal_handle: Any) -> CancelResponse:
        log = self.get_node().get_logger()
        log.info("Got request to cancel goal")
        goal = self._active_goal
        if goal is not None and goal.goal_handle == goal_handle:
            self._command = self._hold_command()
            log.info("Canceling active action goal because cancel callback received.")
            goal.set_canceled(self._action_types.Result())
            self._active_goal = None
        return CancelResponse.ACCEPT

    def _hold_command(self) -> tuple[float, ...]:
        raise NotImplementedError

    def _conclude(self, time_ns: int, position: float, velocity: float, effort: float) -> None:
        """The active goal's outcome, if this cycle decides one."""
        goal = self._active_goal
        if goal is None:
            return
        verdict = self.monitor.check(time_ns, self._command[0] - position, velocity)
        if verdict is None:
            return
        reached = verdict == REACHED
        result = self._result(position, effort, reached)
        if reached or self.values["allow_stalling"]:
            goal.set_succeeded(result)
        else:
            goal.set_aborted(result)
        self._active_goal = None

    def _result(self, position: float, effort: float, reached: bool) -> Any:
        return self._action_types.Result(position=position, effort=effort, reached_goal=reached, stalled=not reached)

    def on_cleanup(self, previous_state: Any) -> None:
        self._stop_action()

    on_shutdown = on_cleanup

    def _stop_action(self) -> None:
        if self._goal_timer is not None:
            self.get_node().destroy_timer(self._goal_timer)
            self._goal_timer = None
        if self._action_server is not None:
            self._action_server.destroy()
            self._action_server = None


class _LegacyGripper(GripperActionBase):
    INTERFACE = ""

    def on_init(self) -> None:
        self.get_node().get_logger().warn(
            "[Deprecated]: the `position_controllers/GripperActionController` and "
            "`effort_controllers::GripperActionController` controllers are replaced by "
            "'parallel_gripper_controllers/GripperActionController' controller")
        super().on_init()

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual([f"{self.values['joint']}/{self.INTERFACE}"])

    def state_interface_configuration(self) -> InterfaceConfiguration:
        j = self.values["joint"]
        return InterfaceConfiguration.individual([f"{j}/position", f"{j}/velocity"])

    def on_activate(self, previous_state: Any) -> CallbackReturn:
        self._cmd = self._find(self.command_interfaces, self.INTERFACE, "command")
        self._pos = self._find(self.state_interfaces, "position", "state")
        self._vel = self._find(self.state_interfaces, "velocity", "state")
        if self._cmd is None or self._pos is None or self._vel is None:
            return CallbackReturn.ERROR
        v = self.values
        self.monitor = StallMonitor(v["goal_tolerance"], v["stall_velocity_threshold"], v["stall_timeout"])
        self._command = (self._pos.value, v["max_effort"])
        self._computed = 0.0
        self._start_adapter()
        self._start_action_server()
        return CallbackReturn.SUCCESS

    def on_deactivate(self, previous_state: Any) -> None:
        self._cmd = self._pos = self._vel = None

    def _goal_command(self, goal: Any) -> tuple[float, ...]:
        return (goal.command.position, goal.command.max_effort)

    def _hold_command(self) -> tuple[float, ...]:
        return (self._pos.value, self.values["max_effort"])

    def _start_adapter(self) -> None:
        pass

    def update(self, time: Any, period: Any) -> ReturnType:
        target, max_effort = self._command
        position, velocity = self._pos.value, self._vel.value
        now_ns = self.get_node().get_clock().now().nanoseconds
        self._conclude(now_ns, position, velocity, self._computed)
        self._computed = self._command_joint(target, target - position, -velocity, max_effort,
                                             period.nanoseconds * 1e-9)
        return ReturnType.OK

    def _command_joint(self, target: float, error: float, error_dot: float, max_effort: float, dt_s: float) -> float:
        raise NotImplementedError


class PositionGripperActionController(_LegacyGripper):
    """position_controllers/GripperActionController: the goal position, forwarded."""

    INTERFACE = "position"

    def _command_joint(self, target: float, error: float, error_dot: float, max_effort: float, dt_s: float) -> float:
        self._cmd.value = target
        return max_effort


class EffortGripperActionController(_LegacyGripper):
    """effort_controllers/GripperActionController: a PID on the position error, clamped to ±max_effort."""

    INTERFACE = "effort"

    def _start_adapter(self) -> None:
        prefix = f"gains.{self.values['joint']}"
        p, i, d, i_clamp = (float(self.auto_declare(f"{prefix}.{k}", 0.0)) for k in ("p", "i", "d", "i_clamp"))
        self._pid = Pid(PidGains(p, i, d, i_max=abs(i_clamp), i_min=-abs(i_clamp)))

    def _command_joint(self, target: float, error: float, error_dot: float, max_effort: float, dt_s: float) -> float:
        effort = self._pid.compute_command(error, error_dot, dt_s)
        limit = abs(max_effort)
        effort = min(limit, max(-limit, effort)) if math.isfinite(effort) else 0.0
        self._cmd.value = effort
        return effort
