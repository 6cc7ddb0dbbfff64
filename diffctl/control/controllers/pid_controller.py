"""pid_controller/PidController (Jazzy): one control_toolbox PID per degree of freedom, chainable.

Interfaces, relative to the controller's node:
  ~/reference                 control_msgs/msg/MultiDOFCommand in (values, values_dot), keep last 1, best effort
  ~/measured_state            control_msgs/msg/MultiDOFCommand in, when use_external_measured_states
  ~/controller_state          control_msgs/msg/MultiDOFStateStamped out, every update
  ~/set_feedforward_control   std_srvs/srv/SetBool (deprecated upstream, with its warning)
Claims `<dof>/<command_interface>` commands and `<state dof>/<interface>` states (every interface of
`reference_and_state_interfaces` for every DoF, interface by interface; none with external states). Exports the
same names under the controller as references and as state interfaces (the measured values).

Each update, per DoF whose reference and measurement are numbers: command = feedforward (gain × the reference's
derivative with two interfaces, × the reference with one, when enable_feedforward) + PID(error, error rate), the
error wrapped to [-π, π] with angle_wraparound and the rate measured when the derivative interfaces are there,
else differenced. A DoF without a reference keeps its previous command. Gains are `gains.<dof>.*` (p, i, d,
u/i clamps, antiwindup strategy, tracking_time_constant, error_deadband, feedforward_gain, save_i_term), changeable
while running. `gains.<dof>.activate_state_publisher` is declared but publishes no pid_state here (control_msgs'
PidState is not among diffctl's types).
"""

from __future__ import annotations

import math
from typing import Any

from diffctl.client.interfaces import cls
from diffctl.client.qos import QoSProfile, ReliabilityPolicy, qos_profile_system_default
from diffctl.control.cdr_template import CdrTemplate
from diffctl.control.controller_interface import (
    CallbackReturn,
    ChainableControllerInterface,
    CommandInterface,
    InterfaceConfiguration,
    ReturnType,
    StateInterface,
)
from diffctl.control.controllers.owned_endpoints import OwnedEndpoints
from diffctl.control.controllers.param_decl import (
    Check,
    ParamDecl,
    changed_values,
    declare_all,
    overrides,
    read_declared,
    set_result,
    table,
)
from diffctl.control.controllers.param_rules import RuleCheck
from diffctl.control.math.pid import Pid, PidGains
from diffctl.control.math.trajectory import shortest_angular_distance
from diffctl.control.realtime_publisher import RealtimePublisher
from diffctl.errors import ParameterError

NAN = math.nan
_NS = 1_000_000_000
MULTI_DOF_COMMAND = "control_msgs/msg/MultiDOFCommand"
STATE = "control_msgs/msg/MultiDOFStateStamped"
_NOT_EMPTY = (Check("not_empty", ()),)

STATIC = table([
    ParamDecl("dof_names", "string_array", [], "Specifies dof_names or axes used by the controller. If "
              "'reference_and_state_dof_names' parameter is defined, then only command dof names are defined with "
              "this parameter.", True, (Check("unique", ()), *_NOT_EMPTY)),
    ParamDecl("reference_and_state_dof_names", "string_array", [], "(optional) Specifies dof_names or axes for "
              "getting reference and reading states. This parameter is only relevant when state dof names are "
              "different then command dof names, i.e., when a following controller is used.", True,
              (Check("unique", ()),)),
    ParamDecl("command_interface", "string", "", "Name of the interface used by the controller for writing commands "
              "to the hardware.", True, _NOT_EMPTY),
    ParamDecl("reference_and_state_interfaces", "string_array", [], "Name of the interfaces used by the controller "
              "getting hardware states and reference commands. The second interface should be the derivative of the "
              "first.", True, (*_NOT_EMPTY, RuleCheck("size_gt", (0,)), RuleCheck("size_lt", (3,)))),
    ParamDecl("set_current_state_as_first_setpoint", "bool", True, "When true, the controller will set the current "
              "state as the first setpoint when the controller is activated. This can help to avoid large initial "
              "errors and sudden jumps in the control output when the controller starts.", True),
    ParamDecl("use_external_measured_states", "bool", False, "Use external states from a topic instead from state "
              "interfaces."),
    ParamDecl("enable_feedforward", "bool", False, "Enables feedforward gain. (Will be deprecated in favour of "
              "setting feedforward_gain to a non-zero value.)"),
])  # fmt: skip

_LEGACY = "[Deprecated, see antiwindup_strategy] "
_GAINS: tuple[tuple[str, str, Any, str, tuple[Check, ...]], ...] = (
    ("p", "double", 0.0, "Proportional gain for PID", ()),
    ("i", "double", 0.0, "Integral gain for PID", ()),
    ("d", "double", 0.0, "Derivative gain for PID", ()),
    ("u_clamp_max", "double", math.inf, "Upper output clamp.", ()),
    ("u_clamp_min", "double", -math.inf, "Lower output clamp.", ()),
    ("antiwindup", "bool", False, _LEGACY + "Anti-windup functionality. When set to true, limits\n        the integral "
     "error to prevent windup; otherwise, constrains the\n        integral contribution to the control output. "
     "i_clamp_max and\n        i_clamp_min are applied in both scenarios.", ()),
    ("i_clamp_max", "double", math.inf, _LEGACY + "Upper integral clamp.", ()),
    ("i_clamp_min", "double", -math.inf, _LEGACY + "Lower integral clamp.", ()),
    ("antiwindup_strategy", "string", "legacy", "Specifies the anti-windup strategy. Options: 'back_calculation',\n"
     "        'conditional_integration', 'legacy' or 'none'. Note that the 'back_calculation' strategy use the\n"
     "        tracking_time_constant parameter to tune the anti-windup behavior.",
     (Check("one_of", (["back_calculation", "conditional_integration", "legacy", "none"],)),)),
    ("tracking_time_constant", "double", 0.0, "Specifies the tracking time constant for the 'back_calculation' "
     "strategy. If\n        set to 0.0 when this strategy is selected, a recommended default value will be applied.",
     ()),
    ("error_deadband", "double", 1e-16, "Is used to stop integration when the error is within the given range.", ()),
    ("feedforward_gain", "double", 0.0, "Gain for the feed-forward part.", ()),
    ("angle_wraparound", "bool", False, "For joints that wrap around (i.e., are continuous).\n          Normalizes "
     "position-error to -pi to pi.", ()),
    ("save_i_term", "bool", True, "Indicating if integral term is retained after re-activation", ()),
    ("activate_state_publisher", "bool", False, "Individual state publisher activation for each DOF. If true, the "
     "controller will publish the state of each DOF to the topic `/<controller_name>/<dof_name>/pid_state`.", ()),
)  # fmt: skip


def decls_for(dof_names: list[str]) -> dict[str, ParamDecl]:
    gains = [ParamDecl(f"gains.{dof}.{k}", t, d, text, checks=c) for dof in dof_names for k, t, d, text, c in _GAINS]
    return {**STATIC, **table(gains)}


def pid_gains(v: dict[str, Any], dof: str) -> PidGains:
    """control_toolbox's PidROS reading of `gains.<dof>.*`."""
    g = f"gains.{dof}."
    return PidGains(v[g + "p"], v[g + "i"], v[g + "d"], v[g + "u_clamp_max"], v[g + "u_clamp_min"],
                    v[g + "antiwindup_strategy"], v[g + "i_clamp_max"], v[g + "i_clamp_min"], v[g + "antiwindup"],
                    v[g + "tracking_time_constant"], v[g + "error_deadband"])


class PidController(ChainableControllerInterface):
    def __init__(self) -> None:
        super().__init__()
        self._endpoints = OwnedEndpoints()
        self._pids: list[Pid] = []
        self._feedforward = False
        self._reference: tuple[list[float], list[float]] = ([], [])
        self._measured: tuple[list[float], list[float]] = ([], [])

    # --- parameters -------------------------------------------------------------------------------------------
    def on_init(self) -> None:
        node = self.get_node()
        dofs = read_declared({"dof_names": STATIC["dof_names"]}, overrides(node), self.get_name())["dof_names"]
        self._decls = decls_for(dofs)
        self.values = declare_all(node, self._decls, self.get_name())
        self._check_gains(self.values)
        node.add_on_set_parameters_callback(self._on_set_parameters)

    def _check_gains(self, v: dict[str, Any]) -> None:
        for dof in v["dof_names"]:
            problem = pid_gains(v, dof).problem()
            if problem is not None:
                raise ParameterError(problem, field=f"{self.get_name()}.gains.{dof}")

    def _on_set_parameters(self, parameters: list[Any]) -> Any:
        if not any(p.name in self._decls for p in parameters):
            return set_result(None)
        try:
            values = read_declared(self._decls, changed_values(self.get_node(), self._decls, parameters),
                                   self.get_name())
            self._check_gains(values)
        except ParameterError as e:
            return set_result(str(e))
        self._pending = values  # taken by the next update (PidROS's parameter callback, the listener's is_old)
        return set_result(None)

    def _take_parameters(self, v: dict[str, Any]) -> None:
        self.values = v
        self._feedforward = v["enable_feedforward"]
        for pid, dof in zip(self._pids, v["dof_names"], strict=False):
            pid.set_gains(pid_gains(v, dof))

    @property
    def _dofs(self) -> list[str]:
        return list(self.values["dof_names"])

    @property
    def _state_dofs(self) -> list[str]:
        return list(self.values["reference_and_state_dof_names"]) or self._dofs

    @property
    def _interfaces(self) -> list[str]:
        return list(self.values["reference_and_state_interfaces"])

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual([f"{d}/{self.values['command_interface']}" for d in self._dofs])

    def state_interface_configuration(self) -> InterfaceConfiguration:
        if self.values["use_external_measured_states"]:
            return InterfaceConfiguration.none()
        return InterfaceConfiguration.individual([f"{d}/{i}" for i in self._interfaces for d in self._state_dofs])

    def on_export_reference_interfaces(self) -> list[CommandInterface]:
        return [CommandInterface(f"{self.get_name()}/{d}/{i}", NAN) for i in self._interfaces for d in self._state_dofs]

    def on_export_state_interfaces(self) -> list[StateInterface]:
        return [StateInterface(f"{self.get_name()}/{d}/{i}", NAN) for i in self._interfaces for d in self._state_dofs]

    # --- lifecycle ----------------------------------------------------------------------------------------------
    def on_configure(self, previous_state: Any) -> CallbackReturn:
        node = self.get_node()
        log = node.get_logger()
        self._pending = None
        v = read_declared(self._decls, {n: node.get_parameter(n).value for n in self._decls}, self.get_name())
        self.values = v
        self._feedforward = v["enable_feedforward"]
        if len(self._state_dofs) != len(self._dofs):
            log.fatal(f"Size of 'dof_names' ({len(self._dofs)}) and 'reference_and_state_dof_names' "
                      f"({len(self._state_dofs)}) parameters has to be the same!")
            return CallbackReturn.FAILURE
        if any(pid_gains(v, d).antiwindup_strategy == "legacy" for d in self._dofs):
            log.warn("Using the legacy anti-windup technique is deprecated. This option will be removed by the ROS 2 "
                     "Kilted Kaiju release.")
        self._pids = [Pid(pid_gains(v, d)) for d in self._dofs]
        n, k = len(self._dofs), len(self._interfaces)
        self._reference = ([NAN] * n, [NAN] * n)
        self._measured = ([NAN] * n, [NAN] * n)
        self._measured_values = [NAN] * (n * k)
        self._endpoints.close_all()
        qos = QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)
        self._endpoints.keep(node.create_subscription(cls(MULTI_DOF_COMMAND), "~/reference", self._on_reference, qos))
        if v["use_external_measured_states"]:
            self._endpoints.keep(node.create_subscription(cls(MULTI_DOF_COMMAND), "~/measured_state",
                                                          self._on_measured_state, qos))
        self._endpoints.keep(node.create_service(cls("std_srvs/srv/SetBool"), "~/set_feedforward_control",
                                                 self._on_set_feedforward))
        state = cls(STATE)()
        state.dof_states = [cls("control_msgs/msg/SingleDOFState")(name=d) for d in self._state_dofs]
        fields = ("reference", "feedback", "feedback_dot", "error", "error_dot", "time_step", "output")
        self._state_cdr = CdrTemplate(state, STATE, [
            ("header.stamp.sec", "i"), ("header.stamp.nanosec", "I"),
            *[(f"dof_states[{i}].{f}", "d") for i in range(n) for f in fields]])
        self._state_values = [0.0] * (n * len(fields))
        pub = node.create_publisher(cls(STATE), "~/controller_state", qos_profile_system_default)
        self._state_pub = self._endpoints.keep(RealtimePublisher(pub))
        log.info("configure successful")
        return CallbackReturn.SUCCESS

    def on_activate(self, previous_state: Any) -> None:
        n = len(self._dofs)
        self._reference = ([NAN] * n, [NAN] * n)
        self._measured = ([NAN] * n, [NAN] * n)
        self._measured_values = [NAN] * len(self._measured_values)
        for h in (*self.reference_interfaces, *self.exported_state_interfaces):
            h.value = NAN
        if self.values["set_current_state_as_first_setpoint"] and not self.values["use_external_measured_states"]:
            for ref, state in zip(self.reference_interfaces, self.state_interfaces, strict=False):
                ref.value = state.value
        for pid, dof in zip(self._pids, self._dofs, strict=True):
            pid.reset(keep_integral=self.values[f"gains.{dof}.save_i_term"])

    def on_cleanup(self, previous_state: Any) -> None:
        self._pids = []
        self._endpoints.close_all()

    def on_shutdown(self, previous_state: Any) -> None:
        self._endpoints.close_all()

    # --- intake (executor thread) ---------------------------------------------------------------------------
    def _on_reference(self, msg: Any) -> None:
        log = self.get_node().get_logger()
        n = len(self._state_dofs)
        values, dots = [float(x) for x in msg.values], [float(x) for x in msg.values_dot]
        if not len(msg.dof_names) and len(values) == n:
            log.warn("Reference massage does not have DoF names defined. Assuming that value have order as defined "
                     "state DoFs")
        elif not (len(msg.dof_names) == n and len(values) == n):
            log.error(f"Size of input data names ({len(msg.dof_names)}) and/or values ({len(values)}) is not "
                      f"matching the expected size ({n}).")
            return
        if any(math.isinf(x) for x in (*values, *dots)):
            log.error("Ignoring a reference with an infinite value: only numbers (or NaN: none) can be commanded")
            return
        # upstream takes the values in the order given (its name lookup compares the list with itself)
        self._reference = (values, (dots + [NAN] * n)[:n])

    def _on_measured_state(self, msg: Any) -> None:
        log = self.get_node().get_logger()
        n = len(self._state_dofs)
        if len(msg.dof_names) != n:
            log.error(f"Size of input data names ({len(msg.dof_names)}) is not matching the expected size ({n}).")
            return
        if len(msg.values) != n:
            log.error(f"Size of input data values ({len(msg.values)}) is not matching the expected size ({n}).")
            return
        dots = [float(x) for x in msg.values_dot]
        if dots:
            if len(self._interfaces) != 2:
                log.error("The reference_and_state_interfaces parameter has to have two interfaces [the interface "
                          "and the derivative of the interface], in order to use the values_dot field.")
                return
            if len(dots) != n:
                log.error(f"Size of input data values_dot ({len(dots)}) is not matching the expected size ({n}).")
                return
        self._measured = ([float(x) for x in msg.values], (dots + [NAN] * n)[:n])

    def _on_set_feedforward(self, request: Any, response: Any) -> Any:
        self._feedforward = bool(request.data)
        self.get_node().get_logger().warn("This service will be deprecated in favour of setting the "
                                          "``feedforward_gain`` parameter to a non-zero value.")
        response.success = True
        return response

    # --- real-time loop -------------------------------------------------------------------------------------------
    def update_reference_from_subscribers(self, time: Any, period: Any) -> ReturnType:
        values, dots = self._reference
        n = len(self._dofs)
        refs = self.reference_interfaces
        two = len(refs) == 2 * n
        used = list(values)
        for i in range(n):
            if not math.isnan(values[i]):
                refs[i].value = values[i]
                if two and not math.isnan(dots[i]):
                    refs[n + i].value = dots[i]
                used[i] = NAN
        if used != values:
            self._reference = (used, dots)  # a reference is taken once
        return ReturnType.OK

    def update_and_write_commands(self, time: Any, period: Any) -> ReturnType:
        pending = getattr(self, "_pending", None)
        if pending is not None:
            self._pending = None
            self._take_parameters(pending)
        v = self.values
        n = len(self._dofs)
        measured = self._measured_values
        if v["use_external_measured_states"]:
            values, dots = self._measured
            measured[:n] = values
            if len(measured) == 2 * n:
                measured[n:] = dots
        else:
            for i, h in enumerate(self.state_interfaces):
                measured[i] = h.value
        for h, x in zip(self.exported_state_interfaces, measured, strict=True):
            h.value = x
        refs = self.reference_interfaces
        two_refs, two_states = len(refs) == 2 * n, len(measured) == 2 * n
        dt_s = period.nanoseconds / _NS
        out = self._state_values
        for i, dof in enumerate(self._dofs):
            g = f"gains.{dof}."
            ref, feedback = refs[i].value, measured[i]
            wraps = v[g + "angle_wraparound"]
            error = shortest_angular_distance(feedback, ref) if wraps else ref - feedback
            ref_dot = refs[n + i].value if two_refs else NAN
            feedback_dot = measured[n + i] if two_states else NAN
            if math.isfinite(ref) and math.isfinite(feedback):
                command = 0.0
                if self._feedforward:
                    base = ref_dot if two_refs else ref
                    if math.isfinite(base):
                        command = base * v[g + "feedforward_gain"]
                if two_refs and two_states and math.isfinite(ref_dot) and math.isfinite(feedback_dot):
                    command += self._pids[i].compute_command(error, ref_dot - feedback_dot, dt_s)
                else:
                    command += self._pids[i].compute_command(error, None, dt_s)
                self.command_interfaces[i].value = command
            k = 7 * i
            out[k:k + 7] = (ref, feedback, feedback_dot if two_refs and two_states else 0.0, error,
                            ref_dot - feedback_dot if two_refs and two_states else 0.0, dt_s,
                            self.command_interfaces[i].value)
        sec, nanosec = divmod(time.nanoseconds, _NS)
        self._state_pub.publish_values(self._state_cdr, (sec, nanosec, *out))
        return ReturnType.OK
