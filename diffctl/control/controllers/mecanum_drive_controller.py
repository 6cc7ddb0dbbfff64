"""mecanum_drive_controller/MecanumDriveController (Jazzy): a body twist in, four wheel velocities and odometry out.

Topics, relative to the controller's node:
  ~/reference         geometry_msgs/msg/TwistStamped in (linear.x, linear.y, angular.z), keep last 1, best effort
  ~/odometry          nav_msgs/msg/Odometry out, every update
  ~/tf_odometry       tf2_msgs/msg/TFMessage out (odom → base), every update, when enable_odom_tf (remap it to /tf)
  ~/controller_state  control_msgs/msg/MecanumDriveControllerState out, every update
Claims `<wheel>/velocity` commands of the four `*_command_joint_name`s and the `<wheel>/velocity` states of the
`*_state_joint_name`s (the command joints where those are empty). Chainable: exports `<controller>/linear/x/velocity`,
`<controller>/linear/y/velocity` and `<controller>/angular/z/velocity`.

As upstream: a reference is used while younger than `reference_timeout`, then the wheels get 0; with a timeout of 0
each reference is used for one cycle only. A zero stamp means "now" (with a warning). The references are NaN after
every cycle. Limits (`linear.x.*`, `linear.y.*`, `angular.z.*`: control_toolbox's rate limiter) apply before the
inverse kinematics; odometry integrates the wheels' measured velocities (math/mecanum_kinematics.py). Beyond the
reference: an infinite or absurd reference (command_sanity) is dropped with a warning, so it never reaches the wheels.
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
)
from diffctl.control.controllers import speed_limit_params
from diffctl.control.controllers.command_sanity import MAX_ANGULAR_RADPS, MAX_LINEAR_MPS, rejection
from diffctl.control.controllers.owned_endpoints import OwnedEndpoints
from diffctl.control.controllers.param_decl import (
    Check,
    ParamDecl,
    changed_values,
    declare_all,
    read_declared,
    set_result,
    table,
)
from diffctl.control.controllers.param_rules import RuleCheck
from diffctl.control.controllers.throttled_log import ThrottledLog
from diffctl.control.math.mecanum_kinematics import MecanumGeometry, MecanumOdometry, wheel_velocities_radps
from diffctl.control.math.speed_limiter import LimitError, SpeedLimiter
from diffctl.control.realtime_publisher import RealtimePublisher
from diffctl.errors import ParameterError, RuntimeFailure

NAN = math.nan
_NS = 1_000_000_000
TWIST_STAMPED = "geometry_msgs/msg/TwistStamped"
ODOMETRY = "nav_msgs/msg/Odometry"
TF_MESSAGE = "tf2_msgs/msg/TFMessage"
STATE = "control_msgs/msg/MecanumDriveControllerState"
WHEELS = ("front_left", "front_right", "rear_right", "rear_left")  # the controller's order
AXES = ("linear.x", "linear.y", "angular.z")
_NOT_EMPTY = (Check("not_empty", ()),)
_STATE_TEXT = ("(optional) Specifies a joint name for reading states of {} wheel. This parameter is only relevant "
               "when state joints are different then command joint, i.e., when a following controller is used.")

DECLS = table([
    ParamDecl("reference_timeout", "double", 0.0, "Timeout for controller references after which they will be reset. "
              "This is especially useful for controllers that can cause unwanted and dangerous behavior if reference "
              "is not reset, e.g., velocity controllers. If value is 0 the reference is reset after each run."),
    *[ParamDecl(f"{w}_wheel_command_joint_name", "string", "", f"Name of the joints for commanding "
                f"{w.replace('_', ' ')} wheel.", True, _NOT_EMPTY) for w in ("front_left", "front_right",
                                                                             "rear_right", "rear_left")],
    *[ParamDecl(f"{w}_wheel_state_joint_name", "string", "", _STATE_TEXT.format(w.replace("_", " ")), True)
      for w in ("front_left", "front_right", "rear_right", "rear_left")],
    ParamDecl("kinematics.base_frame_offset.x", "double", 0.0, "Base frame offset along X axis of base_frame "
              "(base_link frame).", True),
    ParamDecl("kinematics.base_frame_offset.y", "double", 0.0, "Base frame offset along Y axis of base_frame "
              "(base_link frame).", True),
    ParamDecl("kinematics.base_frame_offset.theta", "double", 0.0, "Base frame offset along Theta axis of "
              "base_frame (base_link frame).", True),
    ParamDecl("kinematics.wheels_radius", "double", 0.0, "Wheel's radius.", True, (Check("gt", (0.0,)),)),
    ParamDecl("kinematics.sum_of_robot_center_projection_on_X_Y_axis", "double", 0.0, "Wheels geometric param used "
              "in mecanum wheels' IK. lx and ly represent the distance from the robot's center to the wheels "
              "projected on the x and y axis with origin at robots center respectively, "
              "sum_of_robot_center_projection_on_X_Y_axis = lx+ly", True),
    ParamDecl("tf_frame_prefix_enable", "bool", True, "Enables or disables appending ``tf_frame_prefix`` to tf "
              "frame id's. See its parameter description for more information."),
    ParamDecl("tf_frame_prefix", "string", "", "(optional) Prefix to be appended to the tf frames, will be added to "
              "odom_frame_id and base_frame_id before publishing. If the parameter is empty, controller's namespace "
              "will be used.", True),
    ParamDecl("base_frame_id", "string", "base_link", "Base frame_id set to value of base_frame_id.", True),
    ParamDecl("odom_frame_id", "string", "odom", "Odometry frame_id set to value of odom_frame_id.", True),
    ParamDecl("enable_odom_tf", "bool", True, "Publishing to tf is enabled or disabled?"),
    ParamDecl("twist_covariance_diagonal", "double_array", [0.1] * 6, "Diagonal values of twist covariance matrix.",
              True, also=(RuleCheck("fixed_size", (6,)),)),
    ParamDecl("pose_covariance_diagonal", "double_array", [0.1] * 6, "Diagonal values of pose covariance matrix.",
              True, also=(RuleCheck("fixed_size", (6,)),)),
    *speed_limit_params.axis_decls("linear.x"),
    *speed_limit_params.axis_decls("linear.y"),
    *speed_limit_params.axis_decls("angular.z", rotational=True),
])  # fmt: skip


def frame_prefix(enabled: bool, prefix: str, namespace: str) -> str:
    """The tf prefix: `prefix`, else the namespace; no leading '/', one trailing '/' ("" at the root)."""
    if not enabled:
        return ""
    p = (prefix or namespace).lstrip("/")
    return p if not p or p.endswith("/") else p + "/"


class MecanumDriveController(ChainableControllerInterface):
    def __init__(self) -> None:
        super().__init__()
        self._endpoints = OwnedEndpoints()
        self._runtime: dict[str, Any] | None = None
        self._active = False
        self.exported_reference_interface_names = ["linear/x/velocity", "linear/y/velocity", "angular/z/velocity"]
        self._command_handles: list[Any] = []
        self._state_handles: list[Any] = []
        self._reference: tuple[int, float, float, float] = (0, NAN, NAN, NAN)  # stamp, vx, vy, wz

    # --- parameters and interfaces ---------------------------------------------------------------------------
    def on_init(self) -> None:
        node = self.get_node()
        self.values = declare_all(node, DECLS, self.get_name())
        node.add_on_set_parameters_callback(self._on_set_parameters)

    def _on_set_parameters(self, parameters: list[Any]) -> Any:
        if not any(p.name in DECLS for p in parameters):
            return set_result(None)
        try:
            values = read_declared(DECLS, changed_values(self.get_node(), DECLS, parameters), self.get_name())
            self._limiters_for(values)
        except (ParameterError, LimitError) as e:
            return set_result(str(e))
        self._runtime = values  # taken by the next update, as the parameter listener's try_update_params
        return set_result(None)

    def _joints(self, kind: str) -> list[str]:
        v = self.values
        if kind == "command":
            return [v[f"{w}_wheel_command_joint_name"] for w in WHEELS]
        return [v[f"{w}_wheel_state_joint_name"] or v[f"{w}_wheel_command_joint_name"] for w in WHEELS]

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual([f"{j}/velocity" for j in self._joints("command")])

    def state_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual([f"{j}/velocity" for j in self._joints("state")])

    def on_export_reference_interfaces(self) -> list[CommandInterface]:
        return [CommandInterface(f"{self.get_name()}/{n}", NAN) for n in self.exported_reference_interface_names]

    @staticmethod
    def _limiters_for(values: dict[str, Any]) -> list[SpeedLimiter]:
        out = []
        for axis in AXES:
            try:
                out.append(SpeedLimiter(speed_limit_params.limits(values, axis)))
            except LimitError as e:
                raise LimitError(f"{axis}.{e.field}", f"Failed to configure {axis.replace('.', ' ')} speed "
                                                      f"limiter: {e.message}") from None
        return out

    # --- lifecycle --------------------------------------------------------------------------------------------
    def on_configure(self, previous_state: Any) -> CallbackReturn:
        node = self.get_node()
        log = node.get_logger()
        self.values = v = read_declared(DECLS, {n: node.get_parameter(n).value for n in DECLS}, self.get_name())
        self._runtime = None
        self._geometry = MecanumGeometry(
            v["kinematics.wheels_radius"], v["kinematics.sum_of_robot_center_projection_on_X_Y_axis"],
            v["kinematics.base_frame_offset.x"], v["kinematics.base_frame_offset.y"],
            v["kinematics.base_frame_offset.theta"])
        self.odometry = MecanumOdometry(self._geometry)
        if self._geometry.center_projection_sum_m == 0.0:
            log.warn("kinematics.sum_of_robot_center_projection_on_X_Y_axis is 0: the wheels cannot turn the robot "
                     "and the odometry's rotation is undefined (set lx + ly, the wheels' distances from the centre)")
        try:
            self._limiters = self._limiters_for(v)
        except LimitError as e:
            log.error(e.message)
            return CallbackReturn.ERROR
        self._timeout_ns = round(v["reference_timeout"] * _NS)
        self._enable_tf = v["enable_odom_tf"]
        self._log = ThrottledLog(log)
        self._endpoints.close_all()
        qos = QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)
        self._endpoints.keep(node.create_subscription(cls(TWIST_STAMPED), "~/reference", self._on_reference, qos))
        prefix = frame_prefix(v["tf_frame_prefix_enable"], v["tf_frame_prefix"], node.get_namespace())
        odom_frame, base_frame = prefix + v["odom_frame_id"], prefix + v["base_frame_id"]
        stamp = [("header.stamp.sec", "i"), ("header.stamp.nanosec", "I")]
        odom = cls(ODOMETRY)()
        odom.header.frame_id, odom.child_frame_id = odom_frame, base_frame
        odom.pose.pose.orientation.w = 1.0
        for i in range(6):
            odom.pose.covariance[7 * i] = v["pose_covariance_diagonal"][i]
            odom.twist.covariance[7 * i] = v["twist_covariance_diagonal"][i]
        self._odom_cdr = CdrTemplate(odom, ODOMETRY, [
            *stamp, ("pose.pose.position.x", "d"), ("pose.pose.position.y", "d"), ("pose.pose.orientation.z", "d"),
            ("pose.pose.orientation.w", "d"), ("twist.twist.linear.x", "d"), ("twist.twist.linear.y", "d"),
            ("twist.twist.angular.z", "d")])  # fmt: skip
        tf = cls(TF_MESSAGE)(transforms=[cls("geometry_msgs/msg/TransformStamped")()])
        t = tf.transforms[0]
        t.header.frame_id, t.child_frame_id = odom_frame, base_frame
        t.transform.rotation.w = 1.0
        self._tf_cdr = CdrTemplate(tf, TF_MESSAGE, [
            *[(f"transforms[0].{p}", c) for p, c in stamp], ("transforms[0].transform.translation.x", "d"),
            ("transforms[0].transform.translation.y", "d"), ("transforms[0].transform.rotation.z", "d"),
            ("transforms[0].transform.rotation.w", "d")])  # fmt: skip
        state = cls(STATE)()
        state.header.frame_id = odom_frame
        self._state_cdr = CdrTemplate(state, STATE, [
            *stamp, ("front_left_wheel_velocity", "d"), ("back_left_wheel_velocity", "d"),
            ("back_right_wheel_velocity", "d"), ("front_right_wheel_velocity", "d"),
            ("reference_velocity.linear.x", "d"), ("reference_velocity.linear.y", "d"),
            ("reference_velocity.angular.z", "d")])  # fmt: skip
        self._odom_pub = self._publisher(ODOMETRY, "~/odometry")
        self._tf_pub = self._publisher(TF_MESSAGE, "~/tf_odometry")
        self._state_pub = self._publisher(STATE, "~/controller_state")
        self._reset_buffers()
        log.info("MecanumDriveController configured successfully")
        return CallbackReturn.SUCCESS

    def _publisher(self, type_name: str, topic: str) -> RealtimePublisher:
        pub = self.get_node().create_publisher(cls(type_name), topic, qos_profile_system_default)
        return self._endpoints.keep(RealtimePublisher(pub))

    def _now_ns(self) -> int:
        return self.get_node().get_clock().now().nanoseconds

    def _reset_buffers(self) -> None:
        for ref in self.reference_interfaces:
            ref.value = NAN
        self._history = [(0.0, 0.0, 0.0), (0.0, 0.0, 0.0)]  # second-to-last, last limited commands
        self._reference = (self._now_ns(), NAN, NAN, NAN)

    def on_activate(self, previous_state: Any) -> None:
        commands = {c.name: c for c in self.command_interfaces}
        states = {s.name: s for s in self.state_interfaces}
        self._command_handles = [commands[f"{j}/velocity"] for j in self._joints("command")]
        self._state_handles = [states[f"{j}/velocity"] for j in self._joints("state")]
        self._reset_buffers()
        self._active = True

    def on_deactivate(self, previous_state: Any) -> None:
        self._active = False
        for h in self._command_handles:
            h.value = NAN
        self._reset_buffers()
        self._command_handles, self._state_handles = [], []

    def on_cleanup(self, previous_state: Any) -> None:
        self._endpoints.close_all()

    on_shutdown = on_cleanup

    # --- reference intake (executor thread) ---------------------------------------------------------------------
    def _on_reference(self, msg: Any) -> None:
        twist = msg.twist
        vx, vy, wz = float(twist.linear.x), float(twist.linear.y), float(twist.angular.z)
        given = [0.0 if math.isnan(x) else x for x in (vx, vy, wz)]  # NaN: "no reference", as upstream
        why = rejection(given, (MAX_LINEAR_MPS, MAX_LINEAR_MPS, MAX_ANGULAR_RADPS),
                        ("linear.x", "linear.y", "angular.z"))
        if why is not None:
            self._log.warn("bad", f"Ignoring a reference: {why}; the wheels keep the previous command")
            return
        now_ns = self._now_ns()
        stamp_ns = msg.header.stamp.sec * _NS + msg.header.stamp.nanosec
        if stamp_ns == 0:
            self._log.warn("zero", "Timestamp in header is missing, using current time as command timestamp.")
            stamp_ns = now_ns
        age_ns = now_ns - stamp_ns
        if self._timeout_ns == 0 or age_ns <= self._timeout_ns:
            self._reference = (stamp_ns, vx, vy, wz)
        else:
            self.get_node().get_logger().error(
                f"Received message has timestamp {stamp_ns / _NS:.10f} older by {age_ns / _NS:.10f} than allowed "
                f"timeout ({self._timeout_ns / _NS:.4f}).")
            self._reference = (now_ns, NAN, NAN, NAN)

    # --- real-time loop ---------------------------------------------------------------------------------------------
    def update_reference_from_subscribers(self, time: Any, period: Any) -> ReturnType:
        stamp_ns, vx, vy, wz = ref = self._reference
        if math.isnan(vx) or math.isnan(vy) or math.isnan(wz):
            return ReturnType.OK
        refs = self.reference_interfaces
        if self._timeout_ns == 0 or time.nanoseconds - stamp_ns <= self._timeout_ns:
            refs[0].value, refs[1].value, refs[2].value = vx, vy, wz
            if self._timeout_ns == 0 and self._reference is ref:  # used once
                self._reference = (stamp_ns, NAN, NAN, NAN)
        else:
            refs[0].value = refs[1].value = refs[2].value = 0.0
            if self._reference is ref:
                self._reference = (stamp_ns, NAN, NAN, NAN)
        return ReturnType.OK

    def update_and_write_commands(self, time: Any, period: Any) -> ReturnType:
        if self._runtime is not None:
            v, self._runtime = self._runtime, None
            self._timeout_ns = round(v["reference_timeout"] * _NS)
            self._limiters = self._limiters_for(v)
            self._enable_tf = v["enable_odom_tf"]
        period_s = period.nanoseconds / _NS
        fl, fr, rr, rl = (h.value for h in self._state_handles)
        if not any(math.isnan(x) for x in (fl, fr, rr, rl)):
            self.odometry.update(fl, fr, rr, rl, period_s)
        refs = self.reference_interfaces
        rx, ry, rz = refs[0].value, refs[1].value, refs[2].value
        wheels = self._command_handles
        if not (math.isnan(rx) or math.isnan(ry) or math.isnan(rz)):
            second, last = self._history
            limited = tuple(lim.limit(r, last[k], second[k], period_s)
                            for k, (lim, r) in enumerate(zip(self._limiters, (rx, ry, rz), strict=True)))
            self._history = [last, limited]
            for h, w in zip(wheels, wheel_velocities_radps(self._geometry, *limited), strict=True):
                h.value = w
        else:
            for h in wheels:
                h.value = 0.0
        self._publish(time.nanoseconds, (fl, fr, rr, rl), (rx, ry, rz))
        refs[0].value = refs[1].value = refs[2].value = NAN
        return ReturnType.OK

    def _publish(self, time_ns: int, measured: tuple[float, ...], reference: tuple[float, float, float]) -> None:
        odom = self.odometry
        sec, nanosec = divmod(time_ns, _NS)
        half = odom.heading_rad * 0.5
        qz, qw = math.sin(half), math.cos(half)
        self._odom_pub.publish_values(self._odom_cdr, (sec, nanosec, odom.x_m, odom.y_m, qz, qw, odom.vx_mps,
                                                       odom.vy_mps, odom.wz_radps))
        if self._enable_tf:
            self._tf_pub.publish_values(self._tf_cdr, (sec, nanosec, odom.x_m, odom.y_m, qz, qw))
        fl, fr, rr, rl = measured
        now_sec, now_nanosec = divmod(self._now_ns(), _NS)  # upstream stamps this one with now()
        self._state_pub.publish_values(self._state_cdr, (now_sec, now_nanosec, fl, rl, rr, fr, *reference))

    @property
    def geometry(self) -> MecanumGeometry:
        if not hasattr(self, "_geometry"):
            raise RuntimeFailure("not configured")
        return self._geometry
