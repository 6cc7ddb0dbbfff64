"""joint_trajectory_controller/JointTrajectoryController (Jazzy tip): joint-space trajectories followed in time.

Interfaces, relative to the controller's node /<name>:
  ~/joint_trajectory        trajectory_msgs/msg/JointTrajectory in (fire and forget), SystemDefaultsQoS
  <name>/follow_joint_trajectory   control_msgs/action/FollowJointTrajectory server (monitored, tolerances)
  ~/controller_state        control_msgs/msg/JointTrajectoryControllerState out, every update
  <name>/query_state        control_msgs/srv/QueryTrajectoryState: the desired state at a future time
  ~/speed_scaling_input     control_msgs/msg/SpeedScalingFactor in (transient local), position-only commands
Claims `<command_joint>/<command_interface>` for every pair (plus speed_scaling.command_interface) and
`<joint>/<state_interface>` (plus speed_scaling.state_interface).

Behaviour as the reference: the controller holds the position it was activated at; a new trajectory replaces the
current one at its first sample, starting from the current state (or the last command, with
interpolate_from_desired_state); desired states are splines between the waypoints (trajectory.py), sampled one
period ahead for the command. Path tolerances are checked while moving, goal tolerances after the last waypoint
(within constraints.goal_time, if set); a violation aborts the goal and holds position (or brakes with
decelerate_on_cancel). With only a velocity or only an effort command interface the position and velocity
errors go through one PID per joint (gains.<joint>.*), plus velocity feed-forward (and the trajectory's effort).
Joints the robot description marks continuous take the short way round. A partial goal (allow_partial_joints_goal)
keeps the other joints where they are commanded. Beyond the reference: a trajectory with a non-finite value is
refused, so nothing but numbers reaches the hardware.

Goal outcomes are decided in the control loop and carried out at action_monitor_rate by realtime_goal.py, as
realtime_tools' goal handle does. Parameters: joint_trajectory_params.py.
"""

from __future__ import annotations

import copy
import dataclasses
import math
from typing import Any

from diffctl.client.action.server import ActionServer, CancelResponse, GoalResponse
from diffctl.client.interfaces import cls
from diffctl.client.qos import qos_profile_system_default
from diffctl.control.cdr_template import CdrTemplate
from diffctl.control.controller_interface import (
    CallbackReturn,
    ControllerInterface,
    InterfaceConfiguration,
    ReturnType,
)
from diffctl.control.controllers import joint_trajectory_tolerances as tolerances
from diffctl.control.controllers.joint_trajectory_params import STATIC, JtcParams, all_decls
from diffctl.control.controllers.owned_endpoints import OwnedEndpoints
from diffctl.control.controllers.param_decl import (
    changed_values,
    declare_all,
    overrides,
    read_declared,
    set_result,
)
from diffctl.control.controllers.realtime_goal import RealtimeGoal
from diffctl.control.math.pid import Pid
from diffctl.control.math.trajectory import (
    Trajectory,
    TrajectoryPoint,
    decelerating_stop,
    shortest_angular_distance,
)
from diffctl.control.realtime_publisher import RealtimePublisher
from diffctl.errors import ParameterError, RuntimeFailure

NAN = math.nan
_NS = 1_000_000_000
_FLOAT_EPS = 1.1920928955078125e-07
FOLLOW_JOINT_TRAJECTORY = "control_msgs/action/FollowJointTrajectory"
JOINT_TRAJECTORY = "trajectory_msgs/msg/JointTrajectory"
STATE = "control_msgs/msg/JointTrajectoryControllerState"
QUERY_STATE = "control_msgs/srv/QueryTrajectoryState"
SPEED_SCALING = "control_msgs/msg/SpeedScalingFactor"
_KINDS = ("position", "velocity", "acceleration", "effort")


@dataclasses.dataclass
class Incoming:
    """A received trajectory in the controller's terms (names as sent; waypoints with their time offsets)."""

    joint_names: list[str]
    points: list[TrajectoryPoint]
    stamp_ns: int


def _duration_ns(d: Any) -> int:
    return int(d.sec) * _NS + int(d.nanosec)


def _incoming(msg: Any) -> Incoming:
    points = [TrajectoryPoint([float(x) for x in p.positions], [float(x) for x in p.velocities],
                              [float(x) for x in p.accelerations], [float(x) for x in p.effort],
                              _duration_ns(p.time_from_start)) for p in msg.points]
    return Incoming(list(msg.joint_names), points, _duration_ns(msg.header.stamp))


def _fill_stamp(stamp: Any, time_ns: int) -> None:
    stamp.sec, stamp.nanosec = divmod(time_ns, _NS)


def _set_duration(d: Any, ns: int) -> None:
    d.sec, d.nanosec = divmod(ns, _NS)


def joints_of_description(description: str, joints: list[str]) -> tuple[list[bool], list[float]]:
    """For each joint: whether the robot description makes it continuous (its error wraps around), and its
    velocity limit (0 when not given)."""
    wraps, limits = [False] * len(joints), [0.0] * len(joints)
    if not description.strip():
        return wraps, limits
    from diffctl.description.robot_files import parse_description

    model = parse_description(description, source="robot_description", simulation=False, check_files=False)
    by_name = {j.name: j for j in model.joints}
    for i, name in enumerate(joints):
        j = by_name.get(name)
        if j is None:
            continue
        wraps[i] = j.type == "continuous"
        v = j.limits.velocity
        limits[i] = v if math.isfinite(v) and v > 0 else 0.0
    return wraps, limits


class JointTrajectoryController(ControllerInterface):
    def __init__(self) -> None:
        super().__init__()
        self.params: JtcParams | None = None
        self._new_params: JtcParams | None = None
        self._endpoints = OwnedEndpoints()
        self._action_server: Any = None
        self._goal_timer: Any = None
        self._state_pub: Any = None
        self._subscriber_active = False
        self._wraps: list[bool] = []
        self._velocity_limits: list[float] = []
        self._decelerate_on_cancel = False
        self._trajectory: Trajectory | None = None
        self._current: Incoming | None = None
        self._new: Incoming | None = None
        self._active_goal: RealtimeGoal | None = None
        self._pending_goal = False
        self._holding = True
        self._pids: list[Pid] = []
        self._scaling_factor = 1.0
        self._scaling_factor_cmd = 1.0
        self._scaling_state: Any = None
        self._scaling_command: Any = None
        self._cmd_timeout_s = 0.0
        self._last_commanded_time_ns = 0
        self._traj_time_ns = 0
        self._command_handles: dict[str, list[Any]] = {k: [] for k in _KINDS}  # kind → handles, in command joint order
        self._state_handles: dict[str, list[Any]] = {k: [] for k in _KINDS}  # kind → handles, in joint order

    # --- parameters --------------------------------------------------------------------------------------
    def on_init(self) -> None:
        node = self.get_node()
        self._logger = node.get_logger()
        given = overrides(node)
        name = self.get_name()
        joints = read_declared({"joints": STATIC["joints"]}, given, name)["joints"]
        decls = all_decls(joints)
        self.params = JtcParams.read(given, name)
        self._decls = decls
        self._check_gains(self.params)
        known = set(decls) | {"type", "update_rate", "is_async", "thread_priority", "use_sim_time", "params_file",
                              "fallback_controllers"}
        for key in given:
            if key not in known and not key.startswith("qos_overrides."):
                self._logger.warn(f"unknown parameter '{name}.{key}' is ignored")
        declare_all(node, decls, name)
        node.add_on_set_parameters_callback(self._on_set_parameters)
        try:
            self._wraps, self._velocity_limits = joints_of_description(self.get_robot_description(), list(joints))
        except Exception as e:  # diffctl's parser may refuse what urdf::Model reads: go on without its facts
            self._logger.warn(f"the robot description could not be read ({e}): no joint is treated as continuous")
            self._wraps, self._velocity_limits = [False] * len(joints), [0.0] * len(joints)
        if self.get_update_rate() == 0:
            raise RuntimeFailure("Controller's update rate is set to 0. This should not happen!")
        self._period_ns = int(1e9 / self.get_update_rate())
        p = self.params
        self._decelerate_on_cancel = p.decelerate_on_cancel
        if p.decelerate_on_cancel:
            for i, joint in enumerate(p.joints):
                if p.max_deceleration_on_cancel[i] <= 0.0:
                    self._logger.error(f"Joint [{joint}] invalid max_deceleration_on_cancel "
                                       f"[{p.max_deceleration_on_cancel[i]:.1f}]. Falling back to hold position on "
                                       "cancel.")
                    self._decelerate_on_cancel = False
                    break
                if self._velocity_limits[i] <= 0.0:
                    self._logger.error(f"Joint [{joint}] has invalid joint velocity defined in URDF "
                                       f"[{self._velocity_limits[i]:.1f}]. Falling back to hold position on cancel.")
                    self._decelerate_on_cancel = False
                    break
        if self._decelerate_on_cancel:
            worst_s = max(v / a for v, a in zip(self._velocity_limits, p.max_deceleration_on_cancel, strict=True))
            self._stop_points = math.ceil(worst_s / (self._period_ns / _NS)) + 1

    def _check_gains(self, p: JtcParams) -> None:
        for joint, g in zip(p.joints, p.gains, strict=True):
            problem = g.problem()
            if problem is not None:
                raise ParameterError(problem, field=f"{self.get_name()}.gains.{joint}")

    def _on_set_parameters(self, parameters: list[Any]) -> Any:
        mine = [p for p in parameters if p.name in self._decls]
        if not mine:
            return set_result(None)
        try:
            values = read_declared(self._decls, changed_values(self.get_node(), self._decls, mine), self.get_name())
            new = JtcParams.from_values(values)
            self._check_gains(new)
        except ParameterError as e:
            return set_result(str(e))
        self._new_params = new
        return set_result(None)

    def _p(self) -> JtcParams:
        if self.params is None:
            raise RuntimeFailure(f"controller '{self.get_name()}' has no parameters: on_init was not run")
        return self.params

    def command_interface_configuration(self) -> InterfaceConfiguration:
        p = self._p()
        names = [f"{j}/{k}" for j in (p.command_joints or p.joints) for k in p.command_interfaces]
        if p.scaling_command_interface:
            names.append(p.scaling_command_interface)
        return InterfaceConfiguration.individual(names)

    def state_interface_configuration(self) -> InterfaceConfiguration:
        p = self._p()
        names = [f"{j}/{k}" for j in p.joints for k in p.state_interfaces]
        if p.scaling_state_interface:
            names.append(p.scaling_state_interface)
        return InterfaceConfiguration.individual(names)

    # --- lifecycle ----------------------------------------------------------------------------------------
    def on_configure(self, previous_state: Any) -> Any:
        node = self.get_node()
        log = self._logger
        if self._new_params is not None:
            self.params, self._new_params = self._new_params, None
        p = self._p()
        if p.open_loop_control:
            log.warn("[deprecated] 'open_loop_control' parameter is deprecated. Instead, set the feedback gains to "
                     "zero and use 'interpolate_from_desired_state' parameter")
        self._dof = len(p.joints)
        self._reset()
        self._command_joints = list(p.command_joints) or list(p.joints)
        if not p.command_joints:
            log.info("No specific joint names are used for command interfaces. Using 'joints' parameter.")
        if len(self._command_joints) > self._dof:
            log.error("The 'command_joints' parameter must not exceed the size of the 'joints' parameter.")
            return CallbackReturn.FAILURE
        missing = [j for j in self._command_joints if j not in p.joints]
        if len(self._command_joints) < self._dof and missing:
            log.error("'command_joints' parameter must be a subset of 'joints' parameter, if their size is not equal.")
            return CallbackReturn.FAILURE
        self._cmd_map = ([p.joints.index(j) for j in self._command_joints]
                         if len(self._command_joints) < self._dof else list(range(self._dof)))
        kinds = p.command_interfaces
        self._has_cmd = {k: k in kinds for k in _KINDS}
        self._has_state = {k: k in p.state_interfaces for k in _KINDS}
        self._closed_loop = (self._has_cmd["velocity"] and len(kinds) == 1 and not p.open_loop_control) or (
            self._has_cmd["effort"] and len(kinds) == 1)
        self._pids = [Pid(p.gains[self._cmd_map[i]]) for i in range(len(self._command_joints))] \
            if self._closed_loop else []
        self._tmp_command = [0.0] * self._dof
        if self._has_cmd["velocity"] and len(kinds) == 1 and not (self._has_state["velocity"]
                                                                   and self._has_state["position"]):
            log.error("'velocity' command interface can only be used alone if 'velocity' and 'position' state "
                      "interfaces are present")
            return CallbackReturn.FAILURE
        if self._has_cmd["effort"] and (len(kinds) == 1 or (len(kinds) == 2 and self._has_cmd["position"])) and \
                not (self._has_state["velocity"] and self._has_state["position"]):
            log.error("'effort' command interface can only be used alone or with 'position' command interface if "
                      "'velocity' and 'position' state interfaces are present")
            return CallbackReturn.FAILURE
        if self._decelerate_on_cancel and not self._has_state["velocity"]:
            log.warn("Decelerate on cancel is enabled but hardware does not support velocity state interface. "
                     "Falling back to hold position on cancel.")
            self._decelerate_on_cancel = False
        log.info(f"Command interfaces are [{' '.join(kinds)}] and state interfaces are "
                 f"[{' '.join(p.state_interfaces)}].")
        self._defaults = self._default_tolerances(p)
        self._active_tolerances = self._defaults
        self._interpolate = p.interpolation_method != "none"
        log.info(f"Using '{p.interpolation_method}' interpolation method.")

        self._endpoints.close_all()
        self._endpoints.keep(node.create_subscription(cls(JOINT_TRAJECTORY), "~/joint_trajectory",
                                                      self._on_trajectory, qos_profile_system_default))
        self._state_pub = self._endpoints.keep(RealtimePublisher(
            node.create_publisher(cls(STATE), "~/controller_state", qos_profile_system_default)))
        self._build_state_message()
        if p.allow_partial_joints_goal:
            log.info("Goals with partial set of joints are allowed")
        log.info(f"Action status changes will be monitored at {p.action_monitor_rate_hz:.2f} Hz.")
        self._action_types = cls(FOLLOW_JOINT_TRAJECTORY)
        self._action_server = self._endpoints.keep(ActionServer(
            node, self._action_types, f"{node.get_name()}/follow_joint_trajectory", self._execute_unused,
            goal_callback=self._on_goal, handle_accepted_callback=self._on_goal_accepted,
            cancel_callback=self._on_cancel))
        n = self._dof
        self._state_current = self._sized_state(0.0)
        self._state_desired = self._sized_state(0.0)
        self._state_error = self._sized_state(0.0)
        self._command_next = TrajectoryPoint()
        self._last_commanded = self._sized_state(NAN)
        self._command_current = TrajectoryPoint(*[[NAN] * n if self._has_cmd[k] else [] for k in _KINDS])
        self._endpoints.keep(node.create_service(cls(QUERY_STATE), f"{node.get_name()}/query_state",
                                                 self._on_query_state))
        if not (self._has_cmd["velocity"] or self._has_cmd["acceleration"] or self._has_cmd["effort"]):
            from diffctl.client.qos import DurabilityPolicy

            qos = copy.copy(qos_profile_system_default)  # SystemDefaultsQoS().transient_local()
            qos.durability = DurabilityPolicy.TRANSIENT_LOCAL
            self._endpoints.keep(node.create_subscription(cls(SPEED_SCALING), "~/speed_scaling_input",
                                                          lambda msg: self.set_scaling_factor(msg.factor), qos))
            log.info(f"Setting initial scaling factor to {p.initial_scaling_factor:2f}")
            self._scaling_factor = p.initial_scaling_factor
        else:
            if p.initial_scaling_factor != 1.0:
                log.warn("Speed scaling is currently only supported for position interfaces. If you want to make use "
                         "of speed scaling, please only use a position interface when configuring this controller.")
            self._scaling_factor = 1.0
        if p.scaling_state_interface:
            log.info(f"Using scaling state from the hardware from interface {p.scaling_state_interface}.")
        else:
            log.info("No scaling interface set. This controller will not read speed scaling from the hardware.")
        self._scaling_factor_cmd = self._scaling_factor
        return None

    def _sized_state(self, value: float) -> TrajectoryPoint:
        n = self._dof
        return TrajectoryPoint([value] * n, [value] * n if self._has_state["velocity"] else [],
                               [value] * n if self._has_state["acceleration"] else [], [0.0] * n)

    def _default_tolerances(self, p: JtcParams) -> tolerances.SegmentTolerances:
        return tolerances.from_parameters(p.joints, p.trajectory_tolerance, p.goal_tolerance,
                                          p.stopped_velocity_tolerance, p.goal_time_s)

    def _build_state_message(self) -> None:
        """The controller_state message's fixed layout (names, which arrays are sized) as a CDR template whose
        leaves are the numbers a cycle changes, in the message's byte order."""
        n = self._dof
        msg = cls(STATE)()
        msg.joint_names = list(self._p().joints)
        leaves: list[tuple[str, str]] = [("header.stamp.sec", "i"), ("header.stamp.nanosec", "I")]
        sized = {
            "reference": ("positions", "velocities", "accelerations"),
            "feedback": ("positions", *(("velocities",) if self._has_state["velocity"] else ()),
                         *(("accelerations",) if self._has_state["acceleration"] else ())),
            "output": tuple(f for k, f in zip(_KINDS, ("positions", "velocities", "accelerations", "effort"),
                                              strict=True) if self._has_cmd[k]),
        }
        sized["error"] = sized["feedback"]
        for part in ("reference", "feedback", "error", "output"):
            point = getattr(msg, part)
            for field in ("positions", "velocities", "accelerations", "effort"):
                if field in sized[part]:
                    setattr(point, field, [0.0] * n)
                    leaves += [(f"{part}.{field}[{i}]", "d") for i in range(n)]
            if part in ("reference", "feedback"):
                leaves += [(f"{part}.time_from_start.sec", "i"), (f"{part}.time_from_start.nanosec", "I")]
        leaves.append(("speed_scaling_factor", "d"))
        self._state_layout = sized
        self._state_cdr = CdrTemplate(msg, STATE, leaves)
        self._output_values: list[float] = [0.0] * (n * len(sized["output"]))

    def on_activate(self, previous_state: Any) -> Any:
        if self._new_params is not None:
            self.params, self._new_params = self._new_params, None
        p = self._p()
        log = self._logger
        self._defaults = self._default_tolerances(p)
        self._scaling_state = self._scaling_command = None
        if p.scaling_state_interface:
            self._scaling_state = next((s for s in self.state_interfaces if s.name == p.scaling_state_interface), None)
            if self._scaling_state is None:
                log.error(f"Did not find speed scaling interface '{p.scaling_state_interface}' in state interfaces.")
                return CallbackReturn.ERROR
        if p.scaling_command_interface:
            self._scaling_command = next(
                (c for c in self.command_interfaces if c.name == p.scaling_command_interface), None)
            if self._scaling_command is None:
                log.error(f"Did not find speed scaling interface '{p.scaling_command_interface}' in command "
                          "interfaces.")
                return CallbackReturn.ERROR
        commands = {c.name: c for c in self.command_interfaces}
        states = {s.name: s for s in self.state_interfaces}
        self._command_handles = {k: [] for k in _KINDS}
        self._state_handles = {k: [] for k in _KINDS}
        for kind in p.command_interfaces:
            handles = [commands.get(f"{j}/{kind}") for j in self._command_joints]
            if None in handles:
                log.error(f"Expected {len(self._command_joints)} '{kind}' command interfaces, got "
                          f"{sum(h is not None for h in handles)}.")
                return CallbackReturn.ERROR
            self._command_handles[kind] = handles
        for kind in p.state_interfaces:
            handles = [states.get(f"{j}/{kind}") for j in p.joints]
            if None in handles:
                log.error(f"Expected {self._dof} '{kind}' state interfaces, got {sum(h is not None for h in handles)}.")
                return CallbackReturn.ERROR
            self._state_handles[kind] = handles
        self._trajectory = Trajectory()
        self._current = None
        self._new = None
        self._subscriber_active = True
        self._read_state(self._state_current)
        self._read_state(self._last_commanded)
        if p.set_last_command_interface_value_as_state_on_activation and self._dof == len(self._command_joints):
            self._state_from_commands(self._state_current)
            self._state_from_commands(self._last_commanded)
        for pid in self._pids:
            pid.reset()
        self._last_commanded_time_ns = 0
        self._new = self._hold_position()
        self._holding = True
        if p.cmd_timeout_s > 0.0:
            if p.cmd_timeout_s > self._defaults.goal_time_s:
                self._cmd_timeout_s = p.cmd_timeout_s
            else:
                log.warn(f"Command timeout must be higher than goal_time tolerance ({p.cmd_timeout_s:f} vs. "
                         f"{self._defaults.goal_time_s:f})")
                self._cmd_timeout_s = 0.0
        else:
            self._cmd_timeout_s = 0.0
        return None

    def on_deactivate(self, previous_state: Any) -> None:
        goal = self._active_goal
        if goal is not None:
            self._pending_goal = False
            goal.set_aborted(self._result(self._action_types.Result.INVALID_GOAL,
                                          "Current goal cancelled during deactivate transition."))
            self._active_goal = None
        for i in range(len(self._command_joints)):
            # the position command stays as it is; the derivatives stop
            for kind in ("velocity", "acceleration", "effort"):
                if self._has_cmd[kind]:
                    self._command_handles[kind][i].value = 0.0
        self._command_handles = {k: [] for k in _KINDS}
        self._state_handles = {k: [] for k in _KINDS}
        self._subscriber_active = False
        self._trajectory = None

    def on_error(self, previous_state: Any) -> None:
        self._reset()

    def on_cleanup(self, previous_state: Any) -> None:
        self._close()

    def on_shutdown(self, previous_state: Any) -> None:
        self._close()

    def _close(self) -> None:
        self._subscriber_active = False
        if self._goal_timer is not None:
            self.get_node().destroy_timer(self._goal_timer)
            self._goal_timer = None
        self._endpoints.close_all()
        self._action_server = self._state_pub = None

    def _reset(self) -> None:
        self._subscriber_active = False
        for pid in self._pids:
            pid.reset()
        self._trajectory = None

    # --- state and commands ---------------------------------------------------------------------------------
    def _read_state(self, state: TrajectoryPoint) -> None:
        state.positions = [h.value for h in self._state_handles["position"]]
        if self._has_state["velocity"]:
            state.velocities = [h.value for h in self._state_handles["velocity"]]
            state.accelerations = [h.value for h in self._state_handles["acceleration"]] \
                if self._has_state["acceleration"] else []
        else:
            state.velocities, state.accelerations = [], []
        if self._has_cmd["effort"]:
            state.effort = self._from_commands("effort")

    def _from_commands(self, kind: str) -> list[float]:
        out = [NAN] * self._dof
        for i, h in enumerate(self._command_handles[kind]):
            out[self._cmd_map[i]] = h.value
        return out

    def _commands_finite(self, kind: str) -> bool:
        return all(math.isfinite(h.value) for h in self._command_handles[kind])

    def _state_from_commands(self, state: TrajectoryPoint) -> None:
        """The last commands as the state, per kind where every joint's command is a number (a restart)."""
        for kind, field in (("position", "positions"), ("velocity", "velocities"),
                            ("acceleration", "accelerations"), ("effort", "effort")):
            if self._has_cmd[kind] and self._commands_finite(kind):
                setattr(state, field, self._from_commands(kind))

    def _write(self, kind: str, values: list[float]) -> None:
        cmap = self._cmd_map
        for i, h in enumerate(self._command_handles[kind]):
            h.value = values[cmap[i]]

    def set_scaling_factor(self, factor: float) -> bool:
        if factor < 0:
            self._logger.warn("Scaling factor has to be greater or equal to 0.0 - Ignoring input!")
            return False
        if factor != self._scaling_factor:
            self._logger.info(f"New scaling factor will be {factor:f}")
        self._scaling_factor = factor
        p = self._p()
        if not p.scaling_command_interface and p.scaling_state_interface:
            self._logger.warn("Setting the scaling factor while only one-way communication with the hardware is "
                              "setup. This will likely get overwritten by the hardware again. If available, please "
                              "also setup the speed_scaling_command_interface_name", once=True)
        else:
            self._scaling_factor_cmd = factor
        return True

    # --- trajectories in ------------------------------------------------------------------------------------
    def _problem(self, msg: Any) -> str | None:
        """Why a trajectory is refused (the reference's messages), or None."""
        p = self._p()
        names = list(msg.joint_names)
        if not p.allow_partial_joints_goal and len(names) != self._dof:
            return "Joints on incoming trajectory don't match the controller joints."
        if not names:
            return "Empty joint names on incoming trajectory."
        if not msg.points:
            return "Empty trajectory received."
        unknown = [n for n in names if n not in p.joints]
        if unknown:
            return f"Incoming joint {unknown[0]} doesn't match the controller's joints."
        last = msg.points[-1]
        if not p.allow_nonzero_velocity_at_trajectory_end:
            for i, v in enumerate(last.velocities):
                if abs(v) > _FLOAT_EPS:
                    return f"Velocity of last trajectory point of joint {names[i]} is not zero: {v:.15f}"
        start_ns = _duration_ns(msg.header.stamp)
        if start_ns != 0:
            end_ns = start_ns + _duration_ns(last.time_from_start)
            now_ns = self.get_node().get_clock().now().nanoseconds
            if end_ns < now_ns:
                return (f"Received trajectory with non-zero start time ({start_ns / _NS:f}) that ends in the past "
                        f"({end_ns / _NS:f})")
        previous_ns = 0
        for i, point in enumerate(msg.points):
            t_ns = _duration_ns(point.time_from_start)
            if i > 0 and t_ns <= previous_ns:
                return (f"Time between points {i - 1} and {i} is not strictly increasing, it is {previous_ns / _NS:f} "
                        f"and {t_ns / _NS:f} respectively")
            previous_ns = t_ns
            fields = (("positions", point.positions), ("velocities", point.velocities),
                      ("accelerations", point.accelerations))
            if p.allow_integration_in_goal_trajectories:
                if not any(len(values) for _, values in fields):
                    return "The given trajectory has no position, velocity, or acceleration points."
                for label, values in fields:
                    if len(values) and len(values) != len(names):
                        return (f"Mismatch between joint_names size ({len(names)}) and {label} ({len(values)}) at "
                                f"point #{i}.")
            else:
                for k, (label, values) in enumerate(fields):
                    if (k == 0 or len(values)) and len(values) != len(names):
                        return (f"Mismatch between joint_names size ({len(names)}) and {label} ({len(values)}) at "
                                f"point #{i}.")
            if not self._has_cmd["effort"] and len(point.effort):
                return ("Trajectories with effort fields are only supported for controllers using the 'effort' "
                        "command interface.")
            for label, values in (*fields, ("effort", point.effort)):
                bad = [v for v in values if not math.isfinite(v)]
                if bad:
                    return f"Point #{i} has a non-finite {label} value ({bad[0]}): only numbers can be commanded."
        return None

    def _validated(self, msg: Any) -> bool:
        problem = self._problem(msg)
        if problem is not None:
            self._logger.error(problem)
            return False
        return True

    def _on_trajectory(self, msg: Any) -> None:
        if not self._validated(msg):
            return
        if self._subscriber_active:
            self._new = _incoming(msg)
            self._holding = False

    def _fill_partial(self, incoming: Incoming) -> None:
        """Joints a partial trajectory leaves out keep their commanded (or measured) position, at rest."""
        p = self._p()
        if len(incoming.joint_names) == self._dof:
            return
        for index, joint in enumerate(p.joints):
            if joint in incoming.joint_names:
                continue
            incoming.joint_names.append(joint)
            hold = NAN
            if self._has_cmd["position"]:
                if joint in self._command_joints:
                    hold = self._command_handles["position"][self._command_joints.index(joint)].value
            elif self._has_state["position"]:
                hold = self._state_handles["position"][index].value
            for point in incoming.points:
                if point.positions and not math.isnan(hold):
                    point.positions.append(hold)
                for field in ("velocities", "accelerations", "effort"):
                    values = getattr(point, field)
                    if values:
                        values.append(0.0)

    def _sort(self, incoming: Incoming) -> None:
        order = [self._p().joints.index(n) for n in incoming.joint_names]
        for point in incoming.points:
            for field in ("positions", "velocities", "accelerations", "effort"):
                values = getattr(point, field)
                if not values:
                    continue
                if len(values) != len(order):
                    self._logger.warn(f"Invalid input size ({len(values)}) for sorting")
                    continue
                out = [0.0] * len(order)
                for k, target in enumerate(order):
                    out[target] = values[k]
                setattr(point, field, out)

    def _hold_position(self) -> Incoming:
        """Stay where the joints are now (and remember that tolerances are not checked while holding)."""
        n = self._dof
        point = TrajectoryPoint(list(self._state_current.positions))
        if self._has_cmd["velocity"] or self._has_cmd["acceleration"]:
            point.velocities = [0.0] * n
        if self._has_cmd["acceleration"]:
            point.accelerations = [0.0] * n
        if self._has_cmd["effort"]:
            point.effort = [0.0] * n
        self._holding = True
        return Incoming(list(self._p().joints), [point], 0)

    def _stop(self) -> Incoming:
        """Hold, or brake to a stop within max_deceleration_on_cancel when decelerate_on_cancel is in force."""
        if not self._decelerate_on_cancel:
            return self._hold_position()
        p = self._p()
        points = decelerating_stop(self._state_current.positions, self._state_current.velocities,
                                   list(p.max_deceleration_on_cancel), self._period_ns / _NS, self._stop_points)
        self._holding = True
        return Incoming(list(p.joints), points, 0)

    def _success_point(self) -> Incoming:
        """Keep commanding the last waypoint, whatever its velocity or acceleration."""
        assert self._trajectory is not None and self._trajectory.points
        last = self._trajectory.points[-1].copy()
        last.time_from_start_ns = 0
        self._holding = True
        return Incoming(list(self._p().joints), [last], 0)

    # --- the action -----------------------------------------------------------------------------------------
    def _result(self, code: int, text: str) -> Any:
        return self._action_types.Result(error_code=code, error_string=text)

    def _on_goal(self, goal: Any) -> GoalResponse:
        from diffctl.control.lifecycle import State

        self._logger.info("Received new action goal")
        if self.get_lifecycle_state() is State.INACTIVE:
            self._logger.error("Can't accept new action goals. Controller is not running.")
            return GoalResponse.REJECT
        if not self._validated(goal.trajectory):
            return GoalResponse.REJECT
        self._logger.info("Accepted new action goal")
        return GoalResponse.ACCEPT

    def _on_cancel(self, goal_handle: Any) -> CancelResponse:
        self._logger.info("Got request to cancel goal")
        goal = self._active_goal
        if goal is not None and goal.goal_handle == goal_handle:
            self._logger.info("Canceling active action goal because cancel callback received.")
            self._pending_goal = False
            goal.set_canceled(self._action_types.Result())
            self._active_goal = None
            self._new = self._stop()
        return CancelResponse.ACCEPT

    def _execute_unused(self, goal_handle: Any) -> Any:  # every goal gets its own callback when accepted
        return self._action_types.Result()

    def _on_goal_accepted(self, goal_handle: Any) -> None:
        self._pending_goal = True
        self._preempt()
        request = goal_handle.request
        self._new = _incoming(request.trajectory)
        self._holding = False
        goal = RealtimeGoal(goal_handle, self._feedback_message)
        goal_handle.execute(goal.execute)
        self._active_goal = goal
        errors: list[str] = []
        self._active_tolerances = tolerances.for_goal(self._defaults, _goal_tolerances(request), self._p().joints,
                                                      errors)
        for text in errors:
            self._logger.error(text)
        node = self.get_node()
        if self._goal_timer is not None:
            node.destroy_timer(self._goal_timer)
        from diffctl.client.clock import Clock
        from diffctl.client.clock_type import ClockType

        self._goal_timer = node.create_timer(1.0 / self._p().action_monitor_rate_hz, goal.run_non_realtime,
                                             clock=Clock(clock_type=ClockType.STEADY_TIME))

    def _preempt(self) -> None:
        goal = self._active_goal
        if goal is not None:
            goal.set_aborted(self._result(self._action_types.Result.INVALID_GOAL,
                                          "Current goal preempted by new incoming action."))
            goal.run_non_realtime()
            self._active_goal = None

    def _feedback_message(self, snapshot: tuple[int, TrajectoryPoint, TrajectoryPoint, TrajectoryPoint]) -> Any:
        time_ns, actual, desired, error = snapshot
        fb = self._action_types.Feedback()
        _fill_stamp(fb.header.stamp, time_ns)
        fb.joint_names = list(self._p().joints)
        for target, point in ((fb.actual, actual), (fb.desired, desired), (fb.error, error)):
            _point_to_msg(point, target)
        return fb

    # --- query_state --------------------------------------------------------------------------------------
    def _on_query_state(self, request: Any, response: Any) -> Any:
        from diffctl.control.lifecycle import State

        if self.get_lifecycle_state() is not State.ACTIVE:
            self._logger.error("Can't sample trajectory. Controller is not active.")
            response.success = False
            return response
        response.name = list(self._p().joints)
        state = self._state_current.copy()
        trajectory = self._trajectory
        if trajectory is not None and trajectory.has_points():
            sample = trajectory.sample(_duration_ns(request.time), self._interpolate)
            response.success = sample is not None
            if sample is not None:
                state = sample.point
                if sample.end == len(trajectory.points or []):
                    self._logger.error("Requested sample time precedes the current trajectory end time.")
                    response.success = False
            else:
                self._logger.error("Requested sample time is earlier than the current trajectory start time.")
        else:
            self._logger.error("Currently there is no valid trajectory instance.")
            response.success = False
        response.position = list(state.positions)
        response.velocity = list(state.velocities)
        response.acceleration = list(state.accelerations)
        return response

    # --- real-time loop ---------------------------------------------------------------------------------------
    def update(self, time: Any, period: Any) -> ReturnType:
        if self._scaling_state is not None:
            self._scaling_factor = self._scaling_state.value
        if self._scaling_command is not None:
            self._scaling_command.value = self._scaling_factor_cmd
        if self._new_params is not None:
            self._take_new_params()
        time_ns, period_ns = time.nanoseconds, period.nanoseconds
        goal = self._active_goal
        new = self._new
        if new is not None and new is not self._current and not (self._pending_goal and goal is None):
            self._fill_partial(new)
            self._sort(new)
            assert self._trajectory is not None
            self._trajectory.replace(new.points, new.stamp_ns)
            self._current = new

        current = self._state_current
        current.time_from_start_ns = 0
        self._read_state(current)
        trajectory = self._trajectory
        if trajectory is not None and trajectory.has_points():
            self._follow(trajectory, goal, time_ns, period_ns)
        self._publish_state(time_ns)
        return ReturnType.OK

    def _take_new_params(self) -> None:
        p, self._new_params = self._new_params, None
        assert p is not None
        self.params = p
        self._defaults = self._default_tolerances(p)
        if self._closed_loop:
            for i, pid in enumerate(self._pids):
                pid.set_gains(p.gains[self._cmd_map[i]])

    def _follow(self, trajectory: Trajectory, goal: RealtimeGoal | None, time_ns: int, period_ns: int) -> None:
        p = self.params
        assert p is not None
        log = self._logger
        current = self._state_current
        first_sample = not trajectory.sampled_already
        if first_sample:
            if p.interpolate_from_desired_state or p.open_loop_control:
                if self._last_commanded_time_ns == 0:
                    self._last_commanded_time_ns = time_ns
                trajectory.set_state_before(self._last_commanded_time_ns, self._last_commanded, self._wraps)
            else:
                trajectory.set_state_before(time_ns, current, self._wraps)
            self._traj_time_ns = time_ns
        else:
            self._traj_time_ns += int(period_ns * self._scaling_factor)
        traj_ns = self._traj_time_ns
        desired = trajectory.sample(traj_ns, self._interpolate)
        if desired is not None:
            self._state_desired = desired.point
        self._state_desired.time_from_start_ns = traj_ns - trajectory.start_time_ns
        ahead = trajectory.sample(traj_ns + self._period_ns, self._interpolate, advance=False)
        current.time_from_start_ns = time_ns - trajectory.start_time_ns
        if ahead is None:
            return
        self._command_next = command = ahead.point
        points = trajectory.points
        assert points is not None
        segment_ns = trajectory.start_time_ns + points[ahead.start].time_from_start_ns
        time_difference_s = traj_ns / _NS - segment_ns / _NS
        before_last = ahead.end != len(points)
        holding = self._holding
        if not before_last and not holding and self._cmd_timeout_s > 0.0 and time_difference_s > self._cmd_timeout_s:
            log.warn("Aborted due to command timeout")
            self._new = self._stop()

        tol = self._active_tolerances
        error = self._state_error
        desired_state = self._state_desired
        violated = outside_goal = False
        within_goal_time = True
        for i in range(self._dof):
            self._compute_error(i, current, desired_state)
            e_v = error.velocities[i] if error.velocities else 0.0
            e_a = error.accelerations[i] if error.accelerations else 0.0
            if (before_last or first_sample) and not holding and \
                    not tolerances.within(tol.state[i], error.positions[i], e_v, e_a):
                violated = True
                self._report(i, tol.state[i], error.positions[i], e_v, e_a)
            if not before_last and not holding and \
                    not tolerances.within(tol.goal_state[i], error.positions[i], e_v, e_a):
                outside_goal = True
                if tol.goal_time_s != 0.0 and time_difference_s > tol.goal_time_s:
                    within_goal_time = False
                    self._report(i, tol.goal_state[i], error.positions[i], e_v, e_a)

        if not violated and within_goal_time:
            self._command_joints_from(command, desired_state, period_ns)
            self._last_commanded = command
            self._last_commanded_time_ns = time_ns

        if goal is not None:
            goal.set_feedback((time_ns, current.copy(), desired_state.copy(), error.copy()))
            results = self._action_types.Result
            if violated:
                goal.set_aborted(self._result(results.PATH_TOLERANCE_VIOLATED,
                                              "Aborted due to path tolerance violation"))
                self._active_goal = None
                self._pending_goal = False
                log.warn("Aborted due to state tolerance violation")
                self._new = self._stop()
            elif not before_last:
                if not outside_goal:
                    goal.set_succeeded(self._result(results.SUCCESSFUL, "Goal successfully reached!"))
                    self._active_goal = None
                    self._pending_goal = False
                    log.info("Goal reached, success!")
                    self._new = self._success_point()
                elif not within_goal_time:
                    text = f"Aborted due to goal_time_tolerance exceeding by {time_difference_s:f} seconds"
                    goal.set_aborted(self._result(results.GOAL_TOLERANCE_VIOLATED, text))
                    self._active_goal = None
                    self._pending_goal = False
                    log.warn(text)
                    self._new = self._stop()
        elif violated and not self._pending_goal:
            log.error("Holding position due to state tolerance violation")
            self._new = self._stop()
        elif not before_last and not within_goal_time and not self._pending_goal:
            log.error("Exceeded goal_time_tolerance: holding position...")
            self._new = self._stop()

    def _compute_error(self, i: int, current: TrajectoryPoint, desired: TrajectoryPoint) -> None:
        error = self._state_error
        if self._wraps[i]:
            error.positions[i] = shortest_angular_distance(current.positions[i], desired.positions[i])
        else:
            error.positions[i] = desired.positions[i] - current.positions[i]
        if self._has_state["velocity"] and (self._has_cmd["velocity"] or self._has_cmd["effort"]):
            error.velocities[i] = desired.velocities[i] - current.velocities[i]
        if self._has_state["acceleration"] and self._has_cmd["acceleration"]:
            error.accelerations[i] = desired.accelerations[i] - current.accelerations[i]

    def _report(self, i: int, tol: tolerances.StateTolerance, e_p: float, e_v: float, e_a: float) -> None:
        lines = tolerances.violations(tol, e_p, e_v, e_a)
        if lines:
            self._logger.error(f"State tolerances failed for joint {i}:")
            for line in lines:
                self._logger.error(line)

    def _command_joints_from(self, command: TrajectoryPoint, desired: TrajectoryPoint, period_ns: int) -> None:
        has = self._has_cmd
        if self._closed_loop:
            error = self._state_error
            period_s = period_ns / _NS
            ff = self._p().ff_velocity_scale
            for i, pid in enumerate(self._pids):
                j = self._cmd_map[i]
                e_v = error.velocities[j] if error.velocities else 0.0
                self._tmp_command[j] = command.velocities[j] * ff[j] + \
                    (command.effort[j] if has["effort"] else 0.0) + \
                    pid.compute_command(error.positions[j], e_v, period_s)
        if has["position"]:
            self._write("position", command.positions)
        if has["velocity"]:
            self._write("velocity", self._tmp_command if self._closed_loop else command.velocities)
        if has["acceleration"]:
            self._write("acceleration", command.accelerations)
        if has["effort"]:
            self._write("effort", self._tmp_command if self._closed_loop else desired.effort)

    def _publish_state(self, time_ns: int) -> None:
        pub = self._state_pub
        if pub is None:
            return
        layout = self._state_layout
        desired, current, error = self._state_desired, self._state_current, self._state_error
        values: list[Any] = list(divmod(time_ns, _NS))
        for field in layout["reference"]:
            values += getattr(desired, field) or [0.0] * self._dof
        values += divmod(desired.time_from_start_ns, _NS)
        for field in layout["feedback"]:
            values += getattr(current, field)
        values += divmod(current.time_from_start_ns, _NS)
        for field in layout["error"]:
            values += getattr(error, field)
        if all(self._commands_finite(k) for k in _KINDS if self._has_cmd[k]):
            output: list[float] = []
            for kind in _KINDS:
                if self._has_cmd[kind]:
                    output += self._from_commands(kind)
            self._output_values = output  # kept while some command is not a number, as upstream keeps it
        values += self._output_values
        values.append(self._scaling_factor)
        pub.publish_values(self._state_cdr, values)

    # --- for tests and tools --------------------------------------------------------------------------------
    @property
    def state_reference(self) -> TrajectoryPoint:
        return self._state_desired

    @property
    def state_feedback(self) -> TrajectoryPoint:
        return self._state_current

    @property
    def state_error(self) -> TrajectoryPoint:
        return self._state_error

    def has_active_trajectory(self) -> bool:
        return self._trajectory is not None and self._trajectory.has_points()

    def use_closed_loop_pid_adapter(self) -> bool:
        return self._closed_loop


def _point_to_msg(point: TrajectoryPoint, msg: Any) -> None:
    msg.positions = list(point.positions)
    msg.velocities = list(point.velocities)
    msg.accelerations = list(point.accelerations)
    msg.effort = list(point.effort)
    _set_duration(msg.time_from_start, point.time_from_start_ns)


def _goal_tolerances(goal: Any) -> tolerances.GoalTolerances:
    def entries(items: Any) -> list[tolerances.JointToleranceRequest]:
        return [tolerances.JointToleranceRequest(t.name, t.position, t.velocity, t.acceleration) for t in items]

    return tolerances.GoalTolerances(_duration_ns(goal.goal_time_tolerance) / _NS, entries(goal.path_tolerance),
                                     entries(goal.goal_tolerance))
