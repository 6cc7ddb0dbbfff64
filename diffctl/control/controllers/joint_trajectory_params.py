"""Every parameter of joint_trajectory_controller/JointTrajectoryController (Jazzy), declared once and read into
a dataclass.

`STATIC` is the fixed part of `src/joint_trajectory_controller_parameters.yaml` (ros-controls/ros2_controllers,
branch jazzy, ed360c9): names, types, defaults, descriptions, read-only flags and validation, including the
controller's own `command_interface_type_combinations` / `state_interface_type_combinations` rules. Its
`__map_joints` groups become one entry per joint once `joints` is known (`gains.<joint>.p`,
`constraints.<joint>.goal`, …), as generate_parameter_library's mapped parameters do (`per_joint`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from diffctl.control.controllers.param_decl import Check, ParamDecl, read_declared, table
from diffctl.control.controllers.param_rules import CUSTOM, RuleCheck
from diffctl.control.math.pid import PidGains

ALLOWED_INTERFACES = ("position", "velocity", "acceleration", "effort")


def command_combination_problem(kinds: Sequence[str]) -> str | None:
    """Why a command interface list is not one of effort | velocity | position [velocity [acceleration]] |
    position effort (the reference's messages)."""
    if "velocity" in kinds and len(kinds) > 1 and "position" not in kinds:
        return "'velocity' command interface can be used either alone or 'position' command interface has to be present"
    if "acceleration" in kinds and "velocity" not in kinds and "position" not in kinds:
        return ("'acceleration' command interface can only be used if 'velocity' and 'position' command interfaces "
                "are present")
    if "effort" in kinds and not (len(kinds) == 1 or (len(kinds) == 2 and "position" in kinds)):
        return "'effort' command interface has to be used alone or with a 'position' interface"
    return None


def state_combination_problem(kinds: Sequence[str]) -> str | None:
    if "velocity" in kinds and "position" not in kinds:
        return "'velocity' state interface cannot be used if 'position' interface is missing."
    if "acceleration" in kinds and ("position" not in kinds or "velocity" not in kinds):
        return "'acceleration' state interface cannot be used if 'position' and 'velocity' interfaces are not present."
    return None


CUSTOM["joint_trajectory_controller::command_interface_type_combinations"] = command_combination_problem
CUSTOM["joint_trajectory_controller::state_interface_type_combinations"] = state_combination_problem
_UNIQUE = Check("unique", ())
_SIZE_GT_0 = RuleCheck("size_gt", (0,))

_COMMAND_JOINTS_TEXT = (
    "Joint names to control. If left empty, ``joints`` will be used. This parameters can be used if:\n      \n\n"
    "  * JTC is used in a controller chain where command and state interfaces don't have same names.\n\n"
    "  * If the number of command joints is smaller than the degrees-of-freedom. For example to track the state "
    "and error of passive joints. ``command_joints`` must then be a subset of ``joints``."
)
_INTERPOLATE_TEXT = (
    "Interpolate from the current desired state when receiving a new trajectory.\n      \n\n      The controller "
    "ignores the states provided by hardware interface but using last commands as states for starting the "
    "trajectory interpolation.\n      \n\n      This is useful if hardware states are not following commands, i.e., "
    "an offset between those (typical for hydraulic manipulators).\n      Furthermore, it is necessary if you have a "
    "reference trajectory that you send over multiple messages (e.g. for MPC-style trajectory planning).\n      \n\n"
    "      If this flag is set, the controller tries to read the values from the command interfaces on activation.\n"
    "      If they have real numeric values, those will be used instead of state interfaces.\n      Therefore it is "
    "important set command interfaces to NaN (i.e., ``std::numeric_limits<double>::quiet_NaN()``) or state values "
    "when the hardware is started.\n"
)

STATIC = table([
    ParamDecl("joints", "string_array", [], "Joint names of the system", True, (_UNIQUE, _SIZE_GT_0)),
    ParamDecl("command_joints", "string_array", [], _COMMAND_JOINTS_TEXT, True, (_UNIQUE,)),
    ParamDecl("command_interfaces", "string_array", [], "Command interfaces provided by the hardware interface for "
              "all joints", True, (_UNIQUE, _SIZE_GT_0, RuleCheck("subset_of", (list(ALLOWED_INTERFACES),)),
                                   RuleCheck("joint_trajectory_controller::command_interface_type_combinations"))),
    ParamDecl("state_interfaces", "string_array", [], "State interfaces provided by the hardware for all joints.",
              True, (_UNIQUE, _SIZE_GT_0, RuleCheck("subset_of", (["position", "velocity", "acceleration"],)),
                     RuleCheck("joint_trajectory_controller::state_interface_type_combinations"))),
    ParamDecl("speed_scaling.initial_scaling_factor", "double", 1.0, "The initial value of the scaling factor if no "
              "exchange with hardware takes place.", True, (Check("gt_eq", (0.0,)),)),
    ParamDecl("speed_scaling.state_interface", "string", "", "Fully qualified name of the speed scaling state "
              "interface name", True),
    ParamDecl("speed_scaling.command_interface", "string", "", "Command interface name used for setting the speed "
              "scaling factor on the hardware.", True),
    ParamDecl("allow_partial_joints_goal", "bool", False, "Allow joint goals defining trajectory for only some "
              "joints."),
    ParamDecl("open_loop_control", "bool", False, "deprecated: use ``interpolate_from_desired_state`` and set "
              "feedback gains to zero instead", True),
    ParamDecl("interpolate_from_desired_state", "bool", False, _INTERPOLATE_TEXT, True),
    ParamDecl("allow_integration_in_goal_trajectories", "bool", False, "Allow integration in goal trajectories to "
              "accept goals without position or velocity specified"),
    ParamDecl("set_last_command_interface_value_as_state_on_activation", "bool", True, "When set to true, the last "
              "command interface value is used as both the current state and the last commanded state upon "
              "activation. If an interface (e.g. velocity) is available only as state and not command, the state is "
              "used. Use this to prevent sagging/jumps on activation when using soft or compliant hardware. When set "
              "to false, the current state is used for both."),
    ParamDecl("action_monitor_rate", "double", 20.0, "Rate to monitor status changes when the controller is "
              "executing action (``control_msgs::action::FollowJointTrajectory``)", True, (Check("gt_eq", (0.1,)),)),
    ParamDecl("interpolation_method", "string", "splines", "The type of interpolation to use, if any", True,
              (Check("one_of", (["splines", "none"],)),)),
    ParamDecl("allow_nonzero_velocity_at_trajectory_end", "bool", False, "If false, the last velocity point has to "
              "be zero or the goal will be rejected"),
    ParamDecl("cmd_timeout", "double", 0.0, "Timeout after which the input command is considered stale.\n     "
              "Timeout is counted from the end of the trajectory (the last point).\n     ``cmd_timeout`` must be "
              "greater than ``constraints.goal_time``, otherwise ignored.\n     If zero, timeout is deactivated"),
    ParamDecl("constraints.stopped_velocity_tolerance", "double", 0.01, "Velocity tolerance for at the end of the "
              "trajectory that indicates that controlled system is stopped."),
    ParamDecl("constraints.goal_time", "double", 0.0, "Time tolerance for achieving trajectory goal before or after "
              "commanded time.\n        If set to zero, the controller will wait a potentially infinite amount of "
              "time.", checks=(Check("gt_eq", (0.0,)),)),
    ParamDecl("constraints.decelerate_on_cancel", "bool", False, "If true and each joints max_deceleration_on_cancel "
              "is greater than 0,\n        decelerate to a stop when the request is canceled or the goal constraints "
              "are violated.\n        Requires velocity state interface from all joints in the controller.", True),
])  # fmt: skip

# The `__map_joints` groups: (suffix, type, default, description, read_only, checks)
_GAINS: tuple[tuple[str, str, Any, str, bool, tuple[Check, ...]], ...] = (
    ("p", "double", 0.0, "Proportional gain :math:`k_p` for PID", False, ()),
    ("i", "double", 0.0, "Integral gain :math:`k_i` for PID", False, ()),
    ("d", "double", 0.0, "Derivative gain :math:`k_d` for PID", False, ()),
    ("i_clamp", "double", math.inf, "[Deprecated, use i_clamp_max/i_clamp_min] Integral clamp. Symmetrical in both "
     "positive and negative direction.", False, ()),
    ("i_clamp_max", "double", math.inf, "Upper integral clamp.", False, ()),
    ("i_clamp_min", "double", -math.inf, "Lower integral clamp.", False, ()),
    ("ff_velocity_scale", "double", 0.0, "Feed-forward scaling :math:`k_{ff}` of velocity", False, ()),
    ("u_clamp_max", "double", math.inf, "Upper output clamp.", False, ()),
    ("u_clamp_min", "double", -math.inf, "Lower output clamp.", False, ()),
    ("antiwindup_strategy", "string", "legacy", "Specifies the anti-windup strategy. Options: 'back_calculation',\n"
     "        'conditional_integration', 'legacy' or 'none'. Note that the 'back_calculation' strategy use the\n"
     "        tracking_time_constant parameter to tune the anti-windup behavior.", True,
     (Check("one_of", (["back_calculation", "conditional_integration", "legacy", "none"],)),)),
    ("tracking_time_constant", "double", 0.0, "Specifies the tracking time constant for the 'back_calculation' "
     "strategy. If\n        set to 0.0 when this strategy is selected, a recommended default value will be "
     "applied.", False, ()),
    ("error_deadband", "double", 0.0, "Is used to stop integration when the error is within the given range.",
     False, ()),
)  # fmt: skip
_CONSTRAINTS: tuple[tuple[str, str, Any, str, bool, tuple[Check, ...]], ...] = (
    ("trajectory", "double", 0.0, "Per-joint trajectory offset tolerance during movement.", False, ()),
    ("goal", "double", 0.0, "Per-joint trajectory offset tolerance at the goal position.", False, ()),
    ("max_deceleration_on_cancel", "double", 0.0, "Per-joint max acceleration used to calculate the stopping "
     "position when a request is canceled or preempted.", True, (Check("gt_eq", (0.0,)),)),
)


def per_joint(joints: Sequence[str]) -> dict[str, ParamDecl]:
    """The mapped parameters for these joints (`gains.<joint>.*`, `constraints.<joint>.*`)."""
    out = []
    for joint in joints:
        for group, entries in (("gains", _GAINS), ("constraints", _CONSTRAINTS)):
            for suffix, kind, default, text, read_only, checks in entries:
                out.append(ParamDecl(f"{group}.{joint}.{suffix}", kind, default, text, read_only, checks))
    return table(out)


def all_decls(joints: Sequence[str]) -> dict[str, ParamDecl]:
    return {**STATIC, **per_joint(joints)}


@dataclass(frozen=True)
class JtcParams:
    joints: tuple[str, ...]
    command_joints: tuple[str, ...]
    command_interfaces: tuple[str, ...]
    state_interfaces: tuple[str, ...]
    initial_scaling_factor: float
    scaling_state_interface: str
    scaling_command_interface: str
    allow_partial_joints_goal: bool
    open_loop_control: bool
    interpolate_from_desired_state: bool
    allow_integration_in_goal_trajectories: bool
    set_last_command_interface_value_as_state_on_activation: bool
    action_monitor_rate_hz: float
    interpolation_method: str
    allow_nonzero_velocity_at_trajectory_end: bool
    cmd_timeout_s: float
    stopped_velocity_tolerance: float
    goal_time_s: float
    decelerate_on_cancel: bool
    trajectory_tolerance: tuple[float, ...]  # per joint
    goal_tolerance: tuple[float, ...]
    max_deceleration_on_cancel: tuple[float, ...]
    gains: tuple[PidGains, ...]  # per joint
    ff_velocity_scale: tuple[float, ...]

    @classmethod
    def from_values(cls, v: Mapping[str, Any]) -> JtcParams:
        joints = tuple(v["joints"])
        gains, ff = [], []
        for j in joints:
            g = f"gains.{j}."
            i_clamp = v[g + "i_clamp"]
            # The deprecated symmetric clamp applies only where the one-sided clamps are left infinite.
            i_max = v[g + "i_clamp_max"] if math.isfinite(v[g + "i_clamp_max"]) else i_clamp
            i_min = v[g + "i_clamp_min"] if math.isfinite(v[g + "i_clamp_min"]) else -i_clamp
            gains.append(PidGains(v[g + "p"], v[g + "i"], v[g + "d"], v[g + "u_clamp_max"], v[g + "u_clamp_min"],
                                  v[g + "antiwindup_strategy"], i_max, i_min, False, v[g + "tracking_time_constant"],
                                  v[g + "error_deadband"]))
            ff.append(v[g + "ff_velocity_scale"])
        return cls(
            joints=joints,
            command_joints=tuple(v["command_joints"]),
            command_interfaces=tuple(v["command_interfaces"]),
            state_interfaces=tuple(v["state_interfaces"]),
            initial_scaling_factor=v["speed_scaling.initial_scaling_factor"],
            scaling_state_interface=v["speed_scaling.state_interface"],
            scaling_command_interface=v["speed_scaling.command_interface"],
            allow_partial_joints_goal=v["allow_partial_joints_goal"],
            open_loop_control=v["open_loop_control"],
            interpolate_from_desired_state=v["interpolate_from_desired_state"],
            allow_integration_in_goal_trajectories=v["allow_integration_in_goal_trajectories"],
            set_last_command_interface_value_as_state_on_activation=v[
                "set_last_command_interface_value_as_state_on_activation"],
            action_monitor_rate_hz=v["action_monitor_rate"],
            interpolation_method=v["interpolation_method"],
            allow_nonzero_velocity_at_trajectory_end=v["allow_nonzero_velocity_at_trajectory_end"],
            cmd_timeout_s=v["cmd_timeout"],
            stopped_velocity_tolerance=v["constraints.stopped_velocity_tolerance"],
            goal_time_s=v["constraints.goal_time"],
            decelerate_on_cancel=v["constraints.decelerate_on_cancel"],
            trajectory_tolerance=tuple(v[f"constraints.{j}.trajectory"] for j in joints),
            goal_tolerance=tuple(v[f"constraints.{j}.goal"] for j in joints),
            max_deceleration_on_cancel=tuple(v[f"constraints.{j}.max_deceleration_on_cancel"] for j in joints),
            gains=tuple(gains),
            ff_velocity_scale=tuple(ff),
        )

    @classmethod
    def read(cls, values: Mapping[str, Any], controller: str) -> JtcParams:
        """Validated against the table for the joints `values` names (raises ParameterError)."""
        joints = read_declared({"joints": STATIC["joints"]}, values, controller)["joints"]
        return cls.from_values(read_declared(all_decls(joints), values, controller))
