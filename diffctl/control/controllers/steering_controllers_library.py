"""steering_controllers_library (Jazzy): what the ackermann, bicycle and tricycle steering controllers share.

Topics, relative to the controller's node:
  ~/reference         geometry_msgs/msg/TwistStamped in (linear.x, angular.z), keep last 1, best effort
  ~/odometry          nav_msgs/msg/Odometry out, every update
  ~/tf_odometry       tf2_msgs/msg/TFMessage out, every update, when enable_odom_tf (remap it to /tf)
  ~/controller_state  control_msgs/msg/SteeringControllerStatus out, every update
Claims `<traction joint>/velocity` then `<steering joint>/position` commands, and the traction joints' velocity
(or position, with position_feedback) then the steering joints' position states (`*_state_names` where given).
Chainable: exports `<controller>/linear/velocity` and `<controller>/angular/velocity`. Joint lists with two
entries are ordered right, left.

As upstream: a reference older than `reference_timeout` (default 1 s) is refused; a used reference is cleared when
the timeout is 0; the references are NaN after each cycle and without one the traction wheels get 0 (the steering
stays). Odometry comes from the joints (or the references, open_loop) through math/steering_odometry.py, which also
turns the reference into wheel speeds and steering angles. The deprecated `front_steering`, `front_wheels_names`,
`rear_wheels_names` and their `*_state_names` map onto the traction/steering lists with a warning, as upstream.
Beyond the reference: an infinite or absurd reference is dropped with a warning (and one written by a preceding
controller drives nothing), so nothing but numbers reaches the joints.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
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
from diffctl.control.controllers.command_sanity import MAX_ANGULAR_RADPS, MAX_LINEAR_MPS, rejection
from diffctl.control.controllers.owned_endpoints import OwnedEndpoints
from diffctl.control.controllers.param_decl import Check, ParamDecl, declare_all, read_declared, table
from diffctl.control.controllers.param_rules import RuleCheck
from diffctl.control.controllers.throttled_log import ThrottledLog
from diffctl.control.math.steering_odometry import ACKERMANN, BICYCLE, TRICYCLE, SteeringKinematics
from diffctl.control.realtime_publisher import RealtimePublisher

NAN = math.nan
_NS = 1_000_000_000
TWIST_STAMPED = "geometry_msgs/msg/TwistStamped"
ODOMETRY = "nav_msgs/msg/Odometry"
TF_MESSAGE = "tf2_msgs/msg/TFMessage"
STATUS = "control_msgs/msg/SteeringControllerStatus"
_LIST = (RuleCheck("size_lt", (5,)), Check("unique", ()))
_DEPRECATED_NAMES = "DEPRECATED: Use 'traction_joints_names' or 'steering_joints_names' instead"
_DEPRECATED_STATES = "DEPRECATED: Use 'traction_joints_state_names' or 'steering_joints_state_names' instead"

DECLS = table([
    ParamDecl("reference_timeout", "double", 1.0, "Timeout for controller references after which they will be reset. "
              "This is especially useful for controllers that can cause unwanted and dangerous behavior if reference "
              "is not reset, e.g., velocity controllers. If value is 0 the reference is reset after each run."),
    ParamDecl("front_steering", "bool", True, _DEPRECATED_NAMES, True),
    ParamDecl("rear_wheels_names", "string_array", [], _DEPRECATED_NAMES, True, _LIST),
    ParamDecl("traction_joints_names", "string_array", [], "Names of traction wheel joints. For kinematic "
              "configurations with two traction joints, the expected order is: right joint, left joint.", True, _LIST),
    ParamDecl("front_wheels_names", "string_array", [], "DEPRECATED: Use 'traction_joints_names' or "
              "'steering_joints_names'' instead", True, _LIST),
    ParamDecl("steering_joints_names", "string_array", [], "Names of steering joints. For kinematic configurations "
              "with two steering joints, the expected order is: right joint, left joint. The orientation of the "
              "steering axes is expected as such: When positive steering position value is commanded, then the robot "
              "should turn in positive direction of the z-axis of the vehicle (see REP-103).", True, _LIST),
    ParamDecl("traction_joints_state_names", "string_array", [], "(Optional) Names of tractions joints to read states "
              "from. If not set joint names from 'traction_joints_names' will be used.", True, _LIST),
    ParamDecl("rear_wheels_state_names", "string_array", [], _DEPRECATED_STATES, True, _LIST),
    ParamDecl("steering_joints_state_names", "string_array", [], "(Optional) Names of steering joints to read states "
              "from. If not set joint names from 'steering_joints_names' will be used.", True, _LIST),
    ParamDecl("front_wheels_state_names", "string_array", [], _DEPRECATED_STATES, True, _LIST),
    ParamDecl("open_loop", "bool", False, "Choose if open-loop or not (feedback) is used for odometry calculation."),
    ParamDecl("reduce_wheel_speed_until_steering_reached", "bool", False, "Reduce wheel speed until the steering "
              "angle has been reached."),
    ParamDecl("velocity_rolling_window_size", "int", 10, "The number of velocity samples to average together to "
              "compute the odometry twist.linear.x and twist.angular.z velocities.", also=(Check("gt", (0,)),)),
    ParamDecl("base_frame_id", "string", "base_link", "Base frame_id set to value of base_frame_id."),
    ParamDecl("odom_frame_id", "string", "odom", "Odometry frame_id set to value of odom_frame_id."),
    ParamDecl("enable_odom_tf", "bool", True, "Publishing to tf is enabled or disabled?"),
    ParamDecl("twist_covariance_diagonal", "double_array", [0.0, 7.0, 14.0, 21.0, 28.0, 35.0],
              "diagonal values of twist covariance matrix.", also=(RuleCheck("fixed_size", (6,)),)),
    ParamDecl("pose_covariance_diagonal", "double_array", [0.0, 7.0, 14.0, 21.0, 28.0, 35.0],
              "diagonal values of pose covariance matrix.", also=(RuleCheck("fixed_size", (6,)),)),
    ParamDecl("position_feedback", "bool", False, "Choice of feedback type, if position_feedback is false then "
              "``HW_IF_VELOCITY`` is taken as interface type, if\n    position_feedback is true then "
              "``HW_IF_POSITION`` is taken as interface type"),
])  # fmt: skip

_CONFIG_NAMES = {BICYCLE: "Bicycle", TRICYCLE: "Tricycle", ACKERMANN: "Ackermann"}
_JOINT_COUNTS = {BICYCLE: (1, 1), TRICYCLE: (2, 1), ACKERMANN: (2, 2)}  # traction, steering


class SteeringControllersLibrary(ChainableControllerInterface):
    """The shared controller; a kinematic variant sets CONFIG and VARIANT_DECLS and implements configure_odometry."""

    CONFIG = BICYCLE
    VARIANT_DECLS: Mapping[str, ParamDecl] = {}

    def __init__(self) -> None:
        super().__init__()
        self._endpoints = OwnedEndpoints()
        self.exported_reference_interface_names = ["linear/velocity", "angular/velocity"]
        self._reference: tuple[int, float, float] = (0, NAN, NAN)
        self._traction: list[Any] = []
        self._steering: list[Any] = []
        self._traction_states: list[Any] = []
        self._steering_states: list[Any] = []
        self.odometry = SteeringKinematics()

    @property
    def decls(self) -> dict[str, ParamDecl]:
        return {**DECLS, **self.VARIANT_DECLS}

    def on_init(self) -> None:
        self.values = declare_all(self.get_node(), self.decls, self.get_name())
        self._joint_lists(self.values, warn=False)

    def _read(self) -> dict[str, Any]:
        node = self.get_node()
        return read_declared(self.decls, {n: node.get_parameter(n).value for n in self.decls}, self.get_name())

    def _joint_lists(self, v: dict[str, Any], warn: bool = True) -> None:
        """traction/steering command and state joint lists, the deprecated front/rear names mapped in."""
        log = self.get_node().get_logger()
        lists = {k: list(v[k]) for k in ("traction_joints_names", "steering_joints_names",
                                         "traction_joints_state_names", "steering_joints_state_names")}
        front = v["front_steering"]
        if warn and not front:
            log.warn("DEPRECATED parameter 'front_steering'. Instead, set 'traction_joints_names' or "
                     "'steering_joints_names'")
        for old, kind in (("front_wheels_names", ""), ("rear_wheels_names", ""),
                          ("front_wheels_state_names", "_state"), ("rear_wheels_state_names", "_state")):
            if not v[old]:
                continue
            if warn:
                log.warn(f"DEPRECATED parameter '{old}', set 'traction_joints{kind}_names' or "
                         f"'steering_joints{kind}_names' instead")
            steers = front == old.startswith("front")
            lists[f"{'steering' if steers else 'traction'}_joints{kind}_names"] = list(v[old])
        self._lists = lists

    def configure_odometry(self, v: dict[str, Any]) -> bool:
        """Set the kinematics' wheel parameters (the variant's); False refuses the configuration."""
        raise NotImplementedError

    def command_interface_configuration(self) -> InterfaceConfiguration:
        lists = self._lists
        return InterfaceConfiguration.individual(
            [f"{j}/velocity" for j in lists["traction_joints_names"]]
            + [f"{j}/position" for j in lists["steering_joints_names"]])

    def state_interface_configuration(self) -> InterfaceConfiguration:
        lists = self._lists
        feedback = "position" if self.values["position_feedback"] else "velocity"
        traction = lists["traction_joints_state_names"] or lists["traction_joints_names"]
        steering = lists["steering_joints_state_names"] or lists["steering_joints_names"]
        return InterfaceConfiguration.individual([f"{j}/{feedback}" for j in traction]
                                                 + [f"{j}/position" for j in steering])

    def on_export_reference_interfaces(self) -> list[CommandInterface]:
        return [CommandInterface(f"{self.get_name()}/{n}", NAN) for n in self.exported_reference_interface_names]

    # --- lifecycle ----------------------------------------------------------------------------------------------
    def on_configure(self, previous_state: Any) -> CallbackReturn:
        node = self.get_node()
        log = node.get_logger()
        self.values = v = self._read()
        self._joint_lists(v)
        self.odometry = SteeringKinematics(v["velocity_rolling_window_size"])
        self.odometry.config = self.CONFIG
        if not self.configure_odometry(v):
            return CallbackReturn.ERROR
        name = _CONFIG_NAMES[self.CONFIG]
        want = dict(zip(("traction", "steering"), _JOINT_COUNTS[self.CONFIG], strict=True))
        for kind in ("traction", "steering"):
            count = len(self._lists[f"{kind}_joints_names"])
            if count != want[kind]:
                log.error(f"{name} configuration requires exactly {_count(want[kind])} {kind} joint"
                          f"{'s' if want[kind] > 1 else ''}, but {count} were provided")
                return CallbackReturn.ERROR
        for kind in ("traction", "steering"):
            states = self._lists[f"{kind}_joints_state_names"]
            if states and len(states) != want[kind]:
                log.error(f"{name} configuration requires exactly {_count(want[kind])} {kind} joint"
                          f"{'s' if want[kind] > 1 else ''}, but {len(states)} state interface names were provided")
                return CallbackReturn.ERROR
        self._timeout_ns = round(v["reference_timeout"] * _NS)
        self._log = ThrottledLog(log)
        self._endpoints.close_all()
        qos = QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)
        self._endpoints.keep(node.create_subscription(cls(TWIST_STAMPED), "~/reference", self._on_reference, qos))
        self._reference = (self._now_ns(), NAN, NAN)
        self._build_publishers(v)
        log.info("configure successful")
        return CallbackReturn.SUCCESS

    def _build_publishers(self, v: dict[str, Any]) -> None:
        stamp = [("header.stamp.sec", "i"), ("header.stamp.nanosec", "I")]
        odom = cls(ODOMETRY)()
        odom.header.frame_id, odom.child_frame_id = v["odom_frame_id"], v["base_frame_id"]
        odom.pose.pose.orientation.w = 1.0
        for i in range(6):
            odom.pose.covariance[7 * i] = v["pose_covariance_diagonal"][i]
            odom.twist.covariance[7 * i] = v["twist_covariance_diagonal"][i]
        self._odom_cdr = CdrTemplate(odom, ODOMETRY, [
            *stamp, ("pose.pose.position.x", "d"), ("pose.pose.position.y", "d"), ("pose.pose.orientation.z", "d"),
            ("pose.pose.orientation.w", "d"), ("twist.twist.linear.x", "d"), ("twist.twist.angular.z", "d")])
        tf = cls(TF_MESSAGE)(transforms=[cls("geometry_msgs/msg/TransformStamped")()])
        tr = tf.transforms[0]
        tr.header.frame_id, tr.child_frame_id = v["odom_frame_id"], v["base_frame_id"]
        tr.transform.rotation.w = 1.0
        self._tf_cdr = CdrTemplate(tf, TF_MESSAGE, [
            *[(f"transforms[0].{p}", c) for p, c in stamp], ("transforms[0].transform.translation.x", "d"),
            ("transforms[0].transform.translation.y", "d"), ("transforms[0].transform.rotation.z", "d"),
            ("transforms[0].transform.rotation.w", "d")])  # fmt: skip
        n_t, n_s = len(self._lists["traction_joints_names"]), len(self._lists["steering_joints_names"])
        status = cls(STATUS)()
        status.header.frame_id = v["odom_frame_id"]
        wheels = "traction_wheels_position" if v["position_feedback"] else "traction_wheels_velocity"
        for field, n in ((wheels, n_t), ("linear_velocity_command", n_t), ("steer_positions", n_s),
                         ("steering_angle_command", n_s)):
            setattr(status, field, [0.0] * n)
        # in the message's field order: the wheels' feedback, steering positions, then the two commands
        leaves = [*stamp, *[(f"{wheels}[{i}]", "d") for i in range(n_t)]]
        leaves += [(f"steer_positions[{i}]", "d") for i in range(n_s)]
        leaves += [(f"linear_velocity_command[{i}]", "d") for i in range(n_t)]
        leaves += [(f"steering_angle_command[{i}]", "d") for i in range(n_s)]
        self._status_cdr = CdrTemplate(status, STATUS, leaves)
        self._odom_pub = self._publisher(ODOMETRY, "~/odometry")
        self._tf_pub = self._publisher(TF_MESSAGE, "~/tf_odometry")
        self._status_pub = self._publisher(STATUS, "~/controller_state")

    def _publisher(self, type_name: str, topic: str) -> RealtimePublisher:
        pub = self.get_node().create_publisher(cls(type_name), topic, qos_profile_system_default)
        return self._endpoints.keep(RealtimePublisher(pub))

    def _now_ns(self) -> int:
        return self.get_node().get_clock().now().nanoseconds

    def on_activate(self, previous_state: Any) -> None:
        n_t = len(self._lists["traction_joints_names"])
        self._traction, self._steering = self.command_interfaces[:n_t], self.command_interfaces[n_t:]
        self._traction_states, self._steering_states = self.state_interfaces[:n_t], self.state_interfaces[n_t:]
        self._reference = (self._now_ns(), NAN, NAN)

    def on_deactivate(self, previous_state: Any) -> None:
        for h in (*self._traction, *self._steering):
            h.value = NAN

    def on_cleanup(self, previous_state: Any) -> None:
        self._endpoints.close_all()

    on_shutdown = on_cleanup

    # --- reference intake (executor thread) --------------------------------------------------------------------
    def _on_reference(self, msg: Any) -> None:
        linear, angular = float(msg.twist.linear.x), float(msg.twist.angular.z)
        given = [0.0 if math.isnan(x) else x for x in (linear, angular)]  # NaN: "no reference", as upstream
        why = rejection(given, (MAX_LINEAR_MPS, MAX_ANGULAR_RADPS), ("linear.x", "angular.z"))
        if why is not None:
            self._log.warn("bad", f"Ignoring a reference: {why}; the joints keep the previous command")
            return
        now_ns = self._now_ns()
        stamp_ns = msg.header.stamp.sec * _NS + msg.header.stamp.nanosec
        if stamp_ns == 0:
            self._log.warn("zero", "Timestamp in header is missing, using current time as command timestamp.")
            stamp_ns = now_ns
        age_ns = now_ns - stamp_ns
        if self._timeout_ns == 0 or age_ns <= self._timeout_ns:
            self._reference = (stamp_ns, linear, angular)
        else:
            self.get_node().get_logger().error(
                f"Received message has timestamp {stamp_ns / _NS:.10f} older for {age_ns / _NS:.10f} which is more "
                f"then allowed timeout ({self._timeout_ns / _NS:.4f}).")

    # --- real-time loop ---------------------------------------------------------------------------------------------
    def update_reference_from_subscribers(self, time: Any, period: Any) -> ReturnType:
        stamp_ns, linear, angular = ref = self._reference
        refs = self.reference_interfaces
        if self._timeout_ns == 0 or time.nanoseconds - stamp_ns <= self._timeout_ns:
            if math.isfinite(linear) and math.isfinite(angular):
                refs[0].value, refs[1].value = linear, angular
                if self._timeout_ns == 0 and self._reference is ref:
                    self._reference = (stamp_ns, NAN, NAN)
        elif not (math.isnan(linear) or math.isnan(angular)):
            refs[0].value = refs[1].value = NAN
            if self._reference is ref:
                self._reference = (stamp_ns, NAN, NAN)
        return ReturnType.OK

    def update_odometry(self, dt_s: float, linear: float, angular: float) -> None:
        v = self.values
        if v["open_loop"]:
            self.odometry.update_open_loop(linear, angular, dt_s)
            return
        traction = tuple(h.value for h in self._traction_states)
        steering = tuple(h.value for h in self._steering_states)
        if not all(math.isfinite(x) for x in (*traction, *steering)):
            return
        if v["position_feedback"]:
            self.odometry.update_from_position(traction, steering, dt_s)
        else:
            self.odometry.update_from_velocity(traction, steering, dt_s)

    def update_and_write_commands(self, time: Any, period: Any) -> ReturnType:
        refs = self.reference_interfaces
        linear, angular = refs[0].value, refs[1].value
        self.update_odometry(period.nanoseconds / _NS, linear if math.isfinite(linear) else 0.0,
                             angular if math.isfinite(angular) else 0.0)
        v = self.values
        if math.isfinite(linear) and math.isfinite(angular):
            wheels, angles = self.odometry.commands(linear, angular, v["open_loop"],
                                                    v["reduce_wheel_speed_until_steering_reached"])
            for h, w in zip(self._traction, wheels, strict=True):
                h.value = w
            for h, a in zip(self._steering, angles, strict=True):
                h.value = a
        else:
            for h in self._traction:
                h.value = 0.0
        self._publish(time.nanoseconds)
        refs[0].value = refs[1].value = NAN
        return ReturnType.OK

    def _publish(self, time_ns: int) -> None:
        odom = self.odometry
        sec, nanosec = divmod(time_ns, _NS)
        half = odom.pose.heading_rad * 0.5
        qz, qw = math.sin(half), math.cos(half)
        x, y = odom.pose.x_m, odom.pose.y_m
        self._odom_pub.publish_values(self._odom_cdr, (sec, nanosec, x, y, qz, qw, odom.linear_mps,
                                                       odom.angular_radps))
        if self.values["enable_odom_tf"]:
            self._tf_pub.publish_values(self._tf_cdr, (sec, nanosec, x, y, qz, qw))
        self._status_pub.publish_values(self._status_cdr, (
            sec, nanosec, *[h.value for h in self._traction_states], *[h.value for h in self._steering_states],
            *[h.value for h in self._traction], *[h.value for h in self._steering]))


def _count(n: int) -> str:
    return {1: "one", 2: "two"}[n]
