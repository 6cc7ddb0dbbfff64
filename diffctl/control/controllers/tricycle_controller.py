"""tricycle_controller/TricycleController (Jazzy): one steered, driven wheel (a traction joint on a steering joint).

Topics and services, relative to the controller's node:
  ~/cmd_vel           geometry_msgs/msg/TwistStamped in (linear.x, angular.z), SystemDefaultsQoS
  ~/odom              nav_msgs/msg/Odometry out, every update (the twist only with odom_only_twist)
  /tf                 tf2_msgs/msg/TFMessage out, every update, when enable_odom_tf (default false)
  ~/cmd_ackermann     ackermann_msgs/msg/AckermannDrive out, the limited command (speed in rad/s, as upstream),
                      when publish_ackermann_command
  ~/reset_odometry    std_srvs/srv/Empty
Claims `<traction>/velocity` and `<steering>/position` commands and the same states.

Each update, as upstream: a command older than cmd_vel_timeout (ms) becomes a stop; odometry from the traction
wheel's velocity and the steering angle (or the command, open_loop; non-finite feedback is an error); the twist's
steering angle and wheel speed (math/tricycle_odometry.py), the speed reduced while the steering is far from its
target, then the traction and steering limiters (math/tricycle_limiters.py). Deactivation stops the wheel and
centres the steering. Beyond the reference: a non-finite or absurd command (command_sanity) is dropped with a
warning, so nothing but numbers reaches the joints.
"""

from __future__ import annotations

import math
import struct
from typing import Any

from diffctl.client.interfaces import cls
from diffctl.client.qos import qos_profile_system_default
from diffctl.control.cdr_template import CdrTemplate
from diffctl.control.controller_interface import (
    CallbackReturn,
    ControllerInterface,
    InterfaceConfiguration,
    ReturnType,
)
from diffctl.control.controllers.command_sanity import MAX_ANGULAR_RADPS, MAX_LINEAR_MPS, rejection
from diffctl.control.controllers.owned_endpoints import OwnedEndpoints
from diffctl.control.controllers.param_decl import Check, ParamDecl, declare_all, overrides, read_declared, table
from diffctl.control.controllers.param_rules import RuleCheck
from diffctl.control.controllers.throttled_log import ThrottledLog
from diffctl.control.math.tricycle_limiters import SteeringLimiter, TractionLimiter
from diffctl.control.math.tricycle_odometry import TricycleOdometry, turn_in_scale, wheel_command
from diffctl.control.realtime_publisher import RealtimePublisher

NAN = math.nan
_NS = 1_000_000_000
TWIST_STAMPED = "geometry_msgs/msg/TwistStamped"
ODOMETRY = "nav_msgs/msg/Odometry"
TF_MESSAGE = "tf2_msgs/msg/TFMessage"
ACKERMANN_DRIVE = "ackermann_msgs/msg/AckermannDrive"
_NOT_EMPTY = (Check("not_empty", ()),)
_COV_TEXT = ("Odometry covariance for the encoder output of the robot for the {}. These values should be tuned to "
             "your robot's sample odometry data, but these values are a good place to start: ``[0.001, 0.001, "
             "0.001, 0.001, 0.001, 0.01]``.")
# Keys removed before Jazzy that tricycle YAMLs still carry (gz_ros2_control's demo among them).
_REMOVED = {"use_stamped_vel": "removed in Jazzy: ~/cmd_vel only accepts geometry_msgs/msg/TwistStamped"}

DECLS = table([
    ParamDecl("traction_joint_name", "string", "", "Name of the traction joint", checks=_NOT_EMPTY),
    ParamDecl("steering_joint_name", "string", "", "Name of the steering joint", checks=_NOT_EMPTY),
    ParamDecl("wheelbase", "double", 0.0, "Shortest distance between the front wheel and the rear axle. If this "
              "parameter is wrong, the robot will not behave correctly in curves.", checks=(Check("gt", (0.0,)),)),
    ParamDecl("wheel_radius", "double", 0.0, "Radius of a wheel, i.e., wheels size, used for transformation of linear "
              "velocity into wheel rotations. If this parameter is wrong the robot will move faster or slower then "
              "expected.", checks=(Check("gt", (0.0,)),)),
    ParamDecl("odom_frame_id", "string", "odom", "Name of the frame for odometry. This frame is parent of "
              "``base_frame_id`` when controller publishes odometry."),
    ParamDecl("base_frame_id", "string", "base_link", "Name of the robot's base frame that is child of the odometry "
              "frame."),
    ParamDecl("pose_covariance_diagonal", "double_array", [0.0] * 6, _COV_TEXT.format("pose"),
              also=(RuleCheck("fixed_size", (6,)),)),
    ParamDecl("twist_covariance_diagonal", "double_array", [0.0] * 6, _COV_TEXT.format("speed"),
              also=(RuleCheck("fixed_size", (6,)),)),
    ParamDecl("open_loop", "bool", False, "If set to true the odometry of the robot will be calculated from the "
              "commanded values and not from feedback."),
    ParamDecl("enable_odom_tf", "bool", False, "Publish transformation between ``odom_frame_id`` and "
              "``base_frame_id``."),
    ParamDecl("odom_only_twist", "bool", False, "for doing the pose integration in separate node."),
    ParamDecl("cmd_vel_timeout", "int", 500, "Timeout in milliseconds, after which input command on ``cmd_vel`` topic "
              "is considered staled."),
    ParamDecl("publish_ackermann_command", "bool", False, "Publish limited commands."),
    ParamDecl("velocity_rolling_window_size", "int", 10, "Size of the rolling window for calculation of mean "
              "velocity use in odometry.", checks=(Check("gt", (0,)),)),
    *[ParamDecl(f"traction.{k}", "double", NAN) for k in ("max_velocity", "min_velocity", "max_acceleration",
                                                          "min_acceleration", "max_deceleration", "min_deceleration",
                                                          "max_jerk", "min_jerk")],
    *[ParamDecl(f"steering.{k}", "double", NAN) for k in ("max_position", "min_position", "max_velocity",
                                                          "min_velocity", "max_acceleration", "min_acceleration")],
])  # fmt: skip


def _f32(x: float) -> float:
    """The value as AckermannDrive's float32 field keeps it (upstream's limiter history is those messages)."""
    try:
        return struct.unpack("<f", struct.pack("<f", x))[0]
    except OverflowError:
        return math.copysign(math.inf, x)


class TricycleController(ControllerInterface):
    def __init__(self) -> None:
        super().__init__()
        self._endpoints = OwnedEndpoints()
        self._active = False
        self._command: tuple[int, float, float] | None = None  # stamp, linear, angular
        self._handles: tuple[Any, Any, Any, Any] | None = None

    def on_init(self) -> None:
        node = self.get_node()
        for key, why in _REMOVED.items():
            if key in overrides(node):
                node.get_logger().warn(f"parameter '{self.get_name()}.{key}' is ignored: {why}")
        self.values = declare_all(node, DECLS, self.get_name())

    def command_interface_configuration(self) -> InterfaceConfiguration:
        v = self.values
        return InterfaceConfiguration.individual([f"{v['traction_joint_name']}/velocity",
                                                  f"{v['steering_joint_name']}/position"])

    def state_interface_configuration(self) -> InterfaceConfiguration:
        return self.command_interface_configuration()

    # --- lifecycle --------------------------------------------------------------------------------------------
    def on_configure(self, previous_state: Any) -> CallbackReturn:
        node = self.get_node()
        log = node.get_logger()
        self.values = v = read_declared(DECLS, {n: node.get_parameter(n).value for n in DECLS}, self.get_name())
        self.odometry = TricycleOdometry(v["wheelbase"], v["wheel_radius"], v["velocity_rolling_window_size"])
        self._timeout_ns = v["cmd_vel_timeout"] * 1_000_000
        t = {k: v[f"traction.{k}"] for k in ("min_velocity", "max_velocity", "min_acceleration", "max_acceleration",
                                             "min_deceleration", "max_deceleration", "min_jerk", "max_jerk")}
        try:
            self._traction_limiter = TractionLimiter(**t)
        except ValueError as e:
            log.error(f"Error configuring traction limiter: {e}")
            return CallbackReturn.ERROR
        s = {k: v[f"steering.{k}"] for k in ("min_position", "max_position", "min_velocity", "max_velocity",
                                             "min_acceleration", "max_acceleration")}
        try:
            self._steering_limiter = SteeringLimiter(**s)
        except ValueError as e:
            log.error(f"Error configuring steering limiter: {e}")
            return CallbackReturn.ERROR
        self._reset()
        self._command = (0, 0.0, 0.0)  # zero-stamped: stale at once, so the robot waits for a command
        self._history = [(0.0, 0.0), (0.0, 0.0)]  # (speed, steering) second-to-last, last
        self._log = ThrottledLog(log)
        self._endpoints.close_all()
        stamp = [("header.stamp.sec", "i"), ("header.stamp.nanosec", "I")]
        self._ackermann_pub = None
        if v["publish_ackermann_command"]:
            self._ackermann_pub = self._publisher(ACKERMANN_DRIVE, "~/cmd_ackermann")
            self._ackermann_cdr = CdrTemplate(cls(ACKERMANN_DRIVE)(), ACKERMANN_DRIVE,
                                              [("steering_angle", "f"), ("speed", "f")])
        self._endpoints.keep(node.create_subscription(cls(TWIST_STAMPED), "~/cmd_vel", self._on_cmd_vel,
                                                      qos_profile_system_default))
        odom = cls(ODOMETRY)()
        odom.header.frame_id, odom.child_frame_id = v["odom_frame_id"], v["base_frame_id"]
        for i in range(6):
            odom.pose.covariance[7 * i] = v["pose_covariance_diagonal"][i]
            odom.twist.covariance[7 * i] = v["twist_covariance_diagonal"][i]
        pose_leaves = [] if v["odom_only_twist"] else [
            ("pose.pose.position.x", "d"), ("pose.pose.position.y", "d"), ("pose.pose.orientation.z", "d"),
            ("pose.pose.orientation.w", "d")]
        self._odom_cdr = CdrTemplate(odom, ODOMETRY, [*stamp, *pose_leaves, ("twist.twist.linear.x", "d"),
                                                      ("twist.twist.angular.z", "d")])
        self._odom_pub = self._publisher(ODOMETRY, "~/odom")
        self._tf_pub = None
        if v["enable_odom_tf"]:
            tf = cls(TF_MESSAGE)(transforms=[cls("geometry_msgs/msg/TransformStamped")()])
            tr = tf.transforms[0]
            tr.header.frame_id, tr.child_frame_id = v["odom_frame_id"], v["base_frame_id"]
            self._tf_cdr = CdrTemplate(tf, TF_MESSAGE, [
                *[(f"transforms[0].{p}", c) for p, c in stamp], ("transforms[0].transform.translation.x", "d"),
                ("transforms[0].transform.translation.y", "d"), ("transforms[0].transform.rotation.z", "d"),
                ("transforms[0].transform.rotation.w", "d")])  # fmt: skip
            self._tf_pub = self._publisher(TF_MESSAGE, "/tf")
        self._endpoints.keep(node.create_service(cls("std_srvs/srv/Empty"), "~/reset_odometry", self._reset_odometry))
        return CallbackReturn.SUCCESS

    def _publisher(self, type_name: str, topic: str) -> RealtimePublisher:
        pub = self.get_node().create_publisher(cls(type_name), topic, qos_profile_system_default)
        return self._endpoints.keep(RealtimePublisher(pub))

    def _reset_odometry(self, request: Any, response: Any) -> Any:
        self.odometry.reset()
        self.get_node().get_logger().info("Odometry successfully reset")
        return response

    def _reset(self) -> None:
        if hasattr(self, "odometry"):
            self.odometry.reset()
        self._handles = None
        self._active = False
        self._command = None

    def on_activate(self, previous_state: Any) -> CallbackReturn:
        log = self.get_node().get_logger()
        log.info("On activate: Initialize Joints")
        v = self.values
        commands = {c.name: c for c in self.command_interfaces}
        states = {s.name: s for s in self.state_interfaces}
        traction, steering = f"{v['traction_joint_name']}", f"{v['steering_joint_name']}"
        found = (states.get(f"{traction}/velocity"), commands.get(f"{traction}/velocity"),
                 states.get(f"{steering}/position"), commands.get(f"{steering}/position"))
        for handle, joint in zip(found, (traction, traction, steering, steering), strict=True):
            if handle is None:
                log.error(f"Unable to obtain joint state handle for {joint}")
                return CallbackReturn.ERROR
        self._handles = found  # traction state, traction command, steering state, steering command
        self._active = True
        return CallbackReturn.SUCCESS

    def on_deactivate(self, previous_state: Any) -> None:
        self._active = False
        if self._handles is not None:
            self._handles[1].value = 0.0
            self._handles[3].value = 0.0

    def on_cleanup(self, previous_state: Any) -> None:
        self._reset()
        self._endpoints.close_all()

    on_error = on_cleanup

    def on_shutdown(self, previous_state: Any) -> None:
        self._endpoints.close_all()

    # --- command intake (executor thread) -----------------------------------------------------------------
    def _on_cmd_vel(self, msg: Any) -> None:
        if not self._active:
            self._log.warn("inactive", "Can't accept new commands. subscriber is inactive")
            return
        linear, angular = float(msg.twist.linear.x), float(msg.twist.angular.z)
        why = rejection((linear, angular), (MAX_LINEAR_MPS, MAX_ANGULAR_RADPS), ("linear.x", "angular.z"))
        if why is not None:
            self._log.warn("bad", f"Ignoring a velocity command: {why}; the wheel keeps the previous command")
            return
        stamp_ns = msg.header.stamp.sec * _NS + msg.header.stamp.nanosec
        if stamp_ns == 0:
            self._log.once("zero", "Received TwistStamped with zero timestamp, setting it to current time, this "
                                   "message will only be shown once")
            stamp_ns = self.get_node().get_clock().now().nanoseconds
        self._command = (stamp_ns, linear, angular)

    # --- real-time loop ------------------------------------------------------------------------------------------
    def update(self, time: Any, period: Any) -> ReturnType:
        log = self.get_node().get_logger()
        command = self._command
        if command is None:
            log.warn("Velocity message received was a nullptr.")
            return ReturnType.ERROR
        time_ns, dt_s = time.nanoseconds, period.nanoseconds / _NS
        stamp_ns, linear, angular = command
        if time_ns - stamp_ns > self._timeout_ns:
            linear = angular = 0.0
            self._command = (stamp_ns, 0.0, 0.0)
        traction_state, traction_cmd, steering_state, steering_cmd = self._handles
        wheel_read, angle_read = traction_state.value, steering_state.value
        v = self.values
        if v["open_loop"]:
            self.odometry.update_open_loop(linear, angular, dt_s)
        else:
            if math.isnan(wheel_read) or math.isnan(angle_read):
                log.error("Could not read feedback value")
                return ReturnType.ERROR
            self.odometry.update(wheel_read, angle_read, dt_s)
        self._publish_odometry(time_ns)
        angle, wheel = wheel_command(linear, angular, v["wheelbase"], v["wheel_radius"])
        wheel *= turn_in_scale(abs(angle - angle_read))
        second, last = self._history
        wheel = self._traction_limiter.limit(wheel, last[0], second[0], dt_s)[0]
        angle = self._steering_limiter.limit(angle, last[1], second[1], dt_s)[0]
        self._history = [last, (_f32(wheel), _f32(angle))]
        if self._ackermann_pub is not None:
            self._ackermann_pub.publish_values(self._ackermann_cdr, (angle, wheel))
        traction_cmd.value = wheel
        steering_cmd.value = angle
        return ReturnType.OK

    def _publish_odometry(self, time_ns: int) -> None:
        pose = self.odometry.pose
        sec, nanosec = divmod(time_ns, _NS)
        half = pose.heading_rad * 0.5
        qz, qw = math.sin(half), math.cos(half)
        twist = (self.odometry.linear_mps, self.odometry.angular_radps)
        if self.values["odom_only_twist"]:
            self._odom_pub.publish_values(self._odom_cdr, (sec, nanosec, *twist))
        else:
            self._odom_pub.publish_values(self._odom_cdr, (sec, nanosec, pose.x_m, pose.y_m, qz, qw, *twist))
        if self._tf_pub is not None:
            self._tf_pub.publish_values(self._tf_cdr, (sec, nanosec, pose.x_m, pose.y_m, qz, qw))
