"""diff_drive_controller/DiffDriveController: body twist in, wheel velocities and odometry out (Jazzy tip).

Topics (relative to the controller node /<name>):
  ~/cmd_vel      geometry_msgs/msg/TwistStamped in; only twist.linear.x and twist.angular.z are used
  ~/odom         nav_msgs/msg/Odometry out, at publish_rate
  /tf            tf2_msgs/msg/TFMessage out (odom → base frame), at publish_rate, when enable_odom_tf
  ~/cmd_vel_out  geometry_msgs/msg/TwistStamped out, the limited command of every update, when
                 publish_limited_velocity

Command intake follows Jazzy: a zero stamp means "now"; a command older than cmd_vel_timeout is dropped
with the reason; a stamp in the future is accepted (it times out cmd_vel_timeout after its stamp); in
update(), a command older than the timeout brakes to zero through the limiter (a timeout of 0 disables
both). A command with a NaN or infinite component keeps the previous reference, with a throttled warning.
Until the first command, or the timeout after activation, nothing is written or published. Beyond the
reference: finite but absurd commands (command_sanity) are dropped with a warning.

Chainable, as Jazzy's: configure exports the reference interfaces `<controller>/linear/velocity` and
`<controller>/angular/velocity`; in chained mode (a preceding controller claims them) the references are
what that controller wrote this cycle and ~/cmd_vel is not read.

Parameters are declared on the controller's node from `diff_drive_params.DECLS`. A running controller takes
changes of its limits, cmd_vel_timeout and multipliers on its next update (as rolling's parameter listener);
values that break a rule are refused by the controller; the rest apply at the next configure.

Each update: limiter (jerk → acceleration → velocity) on the references, odometry (open loop from the limited
command, or mean wheel position / velocity feedback; non-finite feedback → ERROR, which makes the manager
deactivate the controller), odom/tf publishing, then the same velocity to every wheel of a side.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from diffctl.client.interfaces import cls
from diffctl.client.qos import qos_profile_system_default
from diffctl.control.cdr_template import CdrTemplate
from diffctl.control.controller_interface import (
    ChainableControllerInterface,
    CommandInterface,
    InterfaceConfiguration,
    ReturnType,
    StateInterface,
)
from diffctl.control.controllers.command_sanity import MAX_ANGULAR_RADPS, MAX_LINEAR_MPS, rejection
from diffctl.control.controllers.diff_drive_params import DECLS, RUNTIME, DiffDriveParams
from diffctl.control.controllers.owned_endpoints import OwnedEndpoints
from diffctl.control.controllers.param_decl import (
    changed_values,
    current_values,
    declare_all,
    overrides,
    read_declared,
    set_result,
)
from diffctl.control.controllers.throttled_log import ThrottledLog
from diffctl.control.math.odometry import Odometry
from diffctl.control.math.speed_limiter import SpeedLimiter
from diffctl.control.realtime_publisher import RealtimePublisher
from diffctl.errors import ParameterError, RuntimeFailure

NAN = math.nan
_OK = ReturnType.OK
_isfinite, _sin, _cos = math.isfinite, math.sin, math.cos
_NS = 1_000_000_000
TWIST_STAMPED = "geometry_msgs/msg/TwistStamped"
ODOMETRY = "nav_msgs/msg/Odometry"
TF_MESSAGE = "tf2_msgs/msg/TFMessage"


def _set_stamp(stamp: Any, time_ns: int) -> None:
    stamp.sec, stamp.nanosec = divmod(time_ns, _NS)


class DiffDriveController(ChainableControllerInterface):
    def __init__(self) -> None:
        super().__init__()
        self.params: DiffDriveParams | None = None
        self._runtime_params: DiffDriveParams | None = None  # accepted by the set callback, taken by update()
        self._params_source: dict[str, Any] = {}
        self.odometry: Odometry | None = None
        self._limiter_linear = SpeedLimiter()
        self._limiter_angular = SpeedLimiter()
        self._subscriber_active = False
        self._endpoints = OwnedEndpoints()
        self._timeout_ns = 0
        self._publish_period_ns = 0
        self._last_publish_ns: int | None = None
        self._odom_needs_init = True
        self._odom_pub: Any = None
        self._tf_pub: Any = None
        self._cmd_out_pub: Any = None
        self._odom_cdr: CdrTemplate | None = None  # set at configure when the publishers take template values
        # (params, wheel separation, left radius, right radius): the derived values of these parameters
        self._geometry: tuple[Any, float, float, float] = (None, NAN, NAN, NAN)
        self._tf_cdr: CdrTemplate | None = None
        self._cmd_out_cdr: CdrTemplate | None = None
        self._left_commands: list[CommandInterface] = []
        self._right_commands: list[CommandInterface] = []
        self._left_feedback: list[StateInterface] = []
        self._right_feedback: list[StateInterface] = []
        self.exported_reference_interface_names = ["linear/velocity", "angular/velocity"]
        self._reset_buffers(0)

    # --- parameters and interfaces ----------------------------------------------------------------------
    def on_init(self) -> None:
        node = self.get_node()
        self._logger = node.get_logger()
        given = overrides(node)
        params, warnings = DiffDriveParams.from_params(given, self.get_name())
        for text in warnings:
            self._logger.warn(text)
        declare_all(node, DECLS, self.get_name())
        self.params = params
        self._params_source = current_values(node, DECLS)
        node.add_on_set_parameters_callback(self._on_set_parameters)

    def _now_ns(self) -> int:
        return self.get_node().get_clock().now().nanoseconds

    def on_set_chained_mode(self, chained_mode: bool) -> bool:
        # The manager switches the mode while the controller is inactive (it restarts an active one): the
        # buffers start over, so no command of the previous source lingers.
        self._reset_buffers(self._now_ns())
        return True

    def _on_set_parameters(self, parameters: list[Any]) -> Any:
        """Refuse a change that breaks a rule; hand limits and timeout to the next update (executor thread)."""
        mine = {p.name for p in parameters if p.name in DECLS}
        if not mine:
            return set_result(None)
        try:
            values = read_declared(DECLS, changed_values(self.get_node(), DECLS, parameters), self.get_name())
            new = DiffDriveParams.from_values(values, self.get_name())
        except ParameterError as e:
            return set_result(str(e))
        if RUNTIME.intersection(mine) and self.params is not None:
            p = self.params
            self._runtime_params = dataclasses.replace(
                p,
                cmd_vel_timeout_s=new.cmd_vel_timeout_s,
                wheel_separation_multiplier=new.wheel_separation_multiplier,
                left_wheel_radius_multiplier=new.left_wheel_radius_multiplier,
                right_wheel_radius_multiplier=new.right_wheel_radius_multiplier,
                linear=new.linear,
                angular=new.angular,
            )
        return set_result(None)

    def _take_runtime_params(self) -> None:
        p, self._runtime_params = self._runtime_params, None
        if p is None:
            return
        self.params = p
        self._limiter_linear = SpeedLimiter(p.linear)
        self._limiter_angular = SpeedLimiter(p.angular)
        self._timeout_ns = round(p.cmd_vel_timeout_s * _NS)
        if self.odometry is not None:
            self.odometry.wheel_separation_m = p.effective_wheel_separation_m
            self.odometry.left_wheel_radius_m = p.left_wheel_radius_m
            self.odometry.right_wheel_radius_m = p.right_wheel_radius_m
        self._logger.info("Parameters were updated")

    def _p(self) -> DiffDriveParams:
        if self.params is None:
            raise RuntimeFailure(f"controller '{self.get_name()}' has no parameters: on_init was not run")
        return self.params

    def command_interface_configuration(self) -> InterfaceConfiguration:
        p = self._p()
        return InterfaceConfiguration.individual([f"{w}/velocity" for w in (*p.left_wheel_names, *p.right_wheel_names)])

    def state_interface_configuration(self) -> InterfaceConfiguration:
        p = self._p()
        if p.open_loop:
            return InterfaceConfiguration.none()
        iface = p.feedback_interface
        return InterfaceConfiguration.individual([f"{w}/{iface}" for w in (*p.left_wheel_names, *p.right_wheel_names)])

    # --- lifecycle ----------------------------------------------------------------------------------------
    def on_configure(self, previous_state: Any) -> None:
        node = self.get_node()
        now = current_values(node, DECLS)
        if now != self._params_source:
            # The reference re-reads parameters that changed since on_init.
            self.params = DiffDriveParams.from_values(read_declared(DECLS, now, self.get_name()), self.get_name())
            self._params_source = now
            self._logger.info("Parameters were updated")
        self._runtime_params = None
        p = self._p()
        self._limiter_linear = SpeedLimiter(p.linear)
        self._limiter_angular = SpeedLimiter(p.angular)
        self.odometry = Odometry(
            p.effective_wheel_separation_m,
            p.left_wheel_radius_m,
            p.right_wheel_radius_m,
            p.velocity_rolling_window_size,
        )
        self._timeout_ns = round(p.cmd_vel_timeout_s * _NS)
        self._publish_period_ns = round(_NS / p.publish_rate_hz)
        self._last_publish_ns = None
        self._odom_needs_init = True
        self._reset_buffers(self._now_ns())

        prefix = p.frame_prefix(node.get_namespace())
        odom_frame, base_frame = prefix + p.odom_frame_id, prefix + p.base_frame_id
        self._close_endpoints()
        self._odom_msg = odom = cls(ODOMETRY)()
        odom.header.frame_id, odom.child_frame_id = odom_frame, base_frame
        odom.pose.pose.orientation.w = 1.0
        for i in range(6):
            odom.pose.covariance[7 * i] = p.pose_covariance_diagonal[i]
            odom.twist.covariance[7 * i] = p.twist_covariance_diagonal[i]
        self._odom_pub = self._publisher(ODOMETRY, "~/odom")
        transform = cls("geometry_msgs/msg/TransformStamped")()
        transform.header.frame_id, transform.child_frame_id = odom_frame, base_frame
        transform.transform.rotation.w = 1.0
        self._tf_msg = cls(TF_MESSAGE)(transforms=[transform])
        self._tf = self._tf_msg.transforms[0]
        self._tf_pub = self._publisher(TF_MESSAGE, "/tf") if p.enable_odom_tf else None
        self._cmd_out_msg = cls(TWIST_STAMPED)()
        self._cmd_out_msg.header.frame_id = base_frame
        self._cmd_out_pub = self._publisher(TWIST_STAMPED, "~/cmd_vel_out") if p.publish_limited_velocity else None
        # The controllers' bus publishers take a template's values: each message's fixed layout becomes a
        # template, and a cycle hands over the stamp and the numbers that change (packed by the publishing
        # thread; frames, covariances and zeros stay as built above).
        stamp = [("header.stamp.sec", "i"), ("header.stamp.nanosec", "I")]
        self._odom_cdr = self._tf_cdr = self._cmd_out_cdr = None
        pubs = (self._odom_pub, self._tf_pub, self._cmd_out_pub)
        if all(hasattr(pub, "publish_values") for pub in pubs if pub is not None):
            self._odom_cdr = CdrTemplate(self._odom_msg, ODOMETRY, [
                *stamp, *_leaves("pose.pose.position", "x", "y"), *_leaves("pose.pose.orientation", "z", "w"),
                *_leaves("twist.twist.linear", "x"), *_leaves("twist.twist.angular", "z"),
            ])  # fmt: skip
        if self._odom_cdr is not None and self._tf_pub is not None:
            self._tf_cdr = CdrTemplate(self._tf_msg, TF_MESSAGE, [
                *[(f"transforms[0].{path}", code) for path, code in stamp],
                *_leaves("transforms[0].transform.translation", "x", "y"),
                *_leaves("transforms[0].transform.rotation", "z", "w"),
            ])  # fmt: skip
        if self._odom_cdr is not None and self._cmd_out_pub is not None:
            self._cmd_out_cdr = CdrTemplate(self._cmd_out_msg, TWIST_STAMPED, [
                *stamp, *_leaves("twist.linear", "x"), *_leaves("twist.angular", "z"),
            ])  # fmt: skip
        self._log = ThrottledLog(self._logger)
        self._endpoints.keep(
            node.create_subscription(cls(TWIST_STAMPED), "~/cmd_vel", self._on_cmd_vel, qos_profile_system_default)
        )

    def _publisher(self, type_name: str, topic: str) -> RealtimePublisher:
        pub = self.get_node().create_publisher(cls(type_name), topic, qos_profile_system_default)
        return self._endpoints.keep(RealtimePublisher(pub))

    def on_activate(self, previous_state: Any) -> None:
        p = self._p()
        commands = {ci.name: ci for ci in self.command_interfaces}
        states = {si.name: si for si in self.state_interfaces}

        def take(table: dict[str, Any], names: tuple[str, ...], iface: str, kind: str) -> list[Any]:
            missing = [n for n in names if f"{n}/{iface}" not in table]
            if missing:
                raise RuntimeFailure(
                    f"unable to obtain joint {kind} handle for {missing[0]!r} ({iface}); "
                    f"this controller was given {sorted(table) or 'none'}"
                )
            return [table[f"{n}/{iface}"] for n in names]

        self._left_commands = take(commands, p.left_wheel_names, "velocity", "command")
        self._right_commands = take(commands, p.right_wheel_names, "velocity", "command")
        if p.open_loop:
            self._left_feedback, self._right_feedback = [], []
        else:
            self._left_feedback = take(states, p.left_wheel_names, p.feedback_interface, "state")
            self._right_feedback = take(states, p.right_wheel_names, p.feedback_interface, "state")
        self._subscriber_active = True

    def on_deactivate(self, previous_state: Any) -> None:
        self._subscriber_active = False
        self._halt()
        self._reset_buffers(self._now_ns())
        self._left_commands, self._right_commands = [], []
        self._left_feedback, self._right_feedback = [], []

    def on_cleanup(self, previous_state: Any) -> None:
        self._reset()
        self._close_endpoints()

    def on_error(self, previous_state: Any) -> None:
        self._reset()

    def on_shutdown(self, previous_state: Any) -> None:
        self._subscriber_active = False
        self._close_endpoints()

    def _reset(self) -> None:
        if self.odometry is not None:
            self.odometry.reset_pose()
        self._odom_needs_init = True
        self._subscriber_active = False
        self._reset_buffers(self._now_ns())

    def _reset_buffers(self, now_ns: int) -> None:
        # No command yet: NaN references write nothing until a command arrives or the timeout brakes.
        self._command: tuple[float, float, int, bool] = (NAN, NAN, now_ns, False)  # linear, angular, stamp, real
        for ref in self.reference_interfaces:
            ref.set_value(NAN)
        self._previous_linear = (0.0, 0.0)  # last and second-to-last limited commands
        self._previous_angular = (0.0, 0.0)
        self._braking_logged_for: int | None = None

    def _halt(self) -> None:
        for handle in (*self._left_commands, *self._right_commands):
            handle.set_value(0.0)

    def _close_endpoints(self) -> None:
        self._endpoints.close_all()
        self._odom_pub = self._tf_pub = self._cmd_out_pub = None

    # --- command intake (bus thread) ----------------------------------------------------------------------
    def _on_cmd_vel(self, msg: Any) -> None:
        if not self._subscriber_active:
            self._log.warn("inactive", "Can't accept new commands. subscriber is inactive")
            return
        linear, angular = float(msg.twist.linear.x), float(msg.twist.angular.z)
        finite = [x if math.isfinite(x) else 0.0 for x in (linear, angular)]  # NaN/inf: handled in update()
        why = rejection(finite, (MAX_LINEAR_MPS, MAX_ANGULAR_RADPS), ("linear.x", "angular.z"))
        if why is not None:
            self._log.warn("bad", f"Ignoring a velocity command: {why}; the wheels keep the previous command")
            return
        now_ns = self._now_ns()
        stamp_ns = msg.header.stamp.sec * _NS + msg.header.stamp.nanosec
        if stamp_ns == 0:
            self._log.once(
                "zero",
                "Received TwistStamped with zero timestamp, setting it to current time, "
                "this message will only be shown once",
            )
            stamp_ns = now_ns
        age_ns = now_ns - stamp_ns
        # Jazzy keeps a message unless it is older than the timeout; a stamp ahead of this clock is kept.
        if self._timeout_ns and age_ns >= self._timeout_ns:
            self._log.warn(
                "stale",
                f"Ignoring the received message (timestamp {stamp_ns / _NS:.6f}) because it is older than the "
                f"current time by {age_ns / _NS:.6f} seconds, which exceeds the allowed timeout "
                f"({self._timeout_ns / _NS:g}) (stamp it with this controller's clock, or with 0 for 'now')",
            )
            return
        if self._subscriber_active:  # re-checked: on_deactivate may have run while this callback did
            self._command = (linear, angular, stamp_ns, True)  # one atomic store, read whole by update()

    # --- real-time loop ---------------------------------------------------------------------------------------
    def update_ns(self, time_ns: int, period_ns: int, intake: bool = True) -> ReturnType:
        """update() on integer nanoseconds, as the manager's cycle calls it (no Time object per cycle); with
        `intake` False, update_and_write_commands alone. The usual update runs in this one frame: after a
        10 ms sleep every function and object a cycle touches is a cache and TLB miss."""
        if intake and not self._chained_mode:
            self._references_from_command(time_ns)
        if self._runtime_params is not None:
            self._take_runtime_params()
        period_s = period_ns * 1e-9
        ref_linear_handle, ref_angular_handle = self.reference_interfaces
        ref_linear, ref_angular = ref_linear_handle.value, ref_angular_handle.value
        if not (_isfinite(ref_linear) and _isfinite(ref_angular)):
            return _OK  # no command yet (or a chained controller wrote none)

        last, second = self._previous_linear
        v = self._limiter_linear.limit(ref_linear, last, second, period_s)
        self._previous_linear = (v, last)
        last, second = self._previous_angular
        w = self._limiter_angular.limit(ref_angular, last, second, period_s)
        self._previous_angular = (w, last)

        p = self.params
        odom = self.odometry
        if p.open_loop and not self._odom_needs_init:  # _update_odometry's usual case, without its frame
            odom.update_open_loop(v, w, time_ns / _NS)
        elif not self._update_odometry(v, w, time_ns, period_s):
            return ReturnType.ERROR

        # ~/cmd_vel_out on every update; odometry and TF at publish_rate
        last_ns, every_ns = self._last_publish_ns, self._publish_period_ns
        odom_due = last_ns is None or time_ns < last_ns or time_ns - last_ns > 2 * every_ns
        if odom_due:
            self._last_publish_ns = time_ns  # first publish, a clock reset, or a long pause: start over
        elif last_ns + every_ns < time_ns:
            self._last_publish_ns = last_ns + every_ns
            odom_due = True
        if self._odom_cdr is None:
            self._publish_messages(time_ns, v, w, odom_due)
        else:
            sec, nanosec = divmod(time_ns, _NS)
            if self._cmd_out_cdr is not None:
                self._cmd_out_pub.publish_values(self._cmd_out_cdr, (sec, nanosec, v, w))
            if odom_due:
                half = odom.heading_rad * 0.5
                qz, qw = _sin(half), _cos(half)  # heading_quaternion(heading)'s z and w, without the call
                x, y = odom.x_m, odom.y_m
                self._odom_pub.publish_values(
                    self._odom_cdr, (sec, nanosec, x, y, qz, qw, odom.linear_mps, odom.angular_radps)
                )
                if self._tf_cdr is not None:
                    self._tf_pub.publish_values(self._tf_cdr, (sec, nanosec, x, y, qz, qw))

        geometry = self._geometry
        if geometry[0] is not p:  # the (frozen) parameters were replaced: derive the wheels again
            geometry = (p, p.effective_wheel_separation_m, p.left_wheel_radius_m, p.right_wheel_radius_m)
            self._geometry = geometry
        half_turn_mps = w * geometry[1] / 2.0  # wheel_velocities_radps, written out
        left, right = (v - half_turn_mps) / geometry[2], (v + half_turn_mps) / geometry[3]
        for handle in self._left_commands:
            handle.value = left  # set_value(), without the call
        for handle in self._right_commands:
            handle.value = right
        return _OK

    def update_reference_from_subscribers(self, time: Any, period: Any) -> ReturnType:
        self._references_from_command(time.nanoseconds)
        return _OK

    def update_and_write_commands(self, time: Any, period: Any) -> ReturnType:
        return self.update_ns(time.nanoseconds, period.nanoseconds, intake=False)

    def _references_from_command(self, time_ns: int) -> None:
        ref_linear, ref_angular = self.reference_interfaces
        linear, angular, stamp_ns, real = self._command
        if self._timeout_ns and time_ns - stamp_ns > self._timeout_ns:
            ref_linear.value = ref_angular.value = 0.0
            if real and self._braking_logged_for != stamp_ns:  # a received command expired
                self._braking_logged_for = stamp_ns
                self._logger.warn("Velocity command timed out. Braking.")
        elif _isfinite(linear) and _isfinite(angular):
            ref_linear.value, ref_angular.value = linear, angular
        elif real:
            self._log.warn(
                "nan",
                "Command message contains NaNs. Not updating reference interfaces. "
                f"(linear.x = {linear!r}, angular.z = {angular!r})",
            )

    def _update_odometry(self, v: float, w: float, time_ns: int, period_s: float) -> bool:
        odom = self.odometry
        p = self.params
        time_s = time_ns / _NS
        if p.open_loop:
            if self._odom_needs_init:
                odom.init(time_s - period_s)
                self._odom_needs_init = False
            odom.update_open_loop(v, w, time_s)
            return True
        left_sum = right_sum = 0.0
        for i, (lh, rh) in enumerate(zip(self._left_feedback, self._right_feedback, strict=True)):
            lv, rv = lh.get_value(), rh.get_value()
            if not (math.isfinite(lv) and math.isfinite(rv)):
                self._logger.error(
                    f"Either the left or right wheel {p.feedback_interface} is invalid for index [{i}] "
                    f"({lh.name} = {lv!r}, {rh.name} = {rv!r})"
                )
                return False
            left_sum += lv
            right_sum += rv
        n = len(self._left_feedback)
        left_mean, right_mean = left_sum / n, right_sum / n
        if p.position_feedback:
            if self._odom_needs_init:
                odom.init(time_s - period_s, left_mean, right_mean)
                self._odom_needs_init = False
            odom.update_from_position(left_mean, right_mean, time_s)
        else:
            if self._odom_needs_init:
                odom.init(time_s - period_s)
                self._odom_needs_init = False
            odom.update_from_step(
                left_mean * p.left_wheel_radius_m * period_s, right_mean * p.right_wheel_radius_m * period_s, time_s
            )
        return True

    def _publish_messages(self, time_ns: int, v: float, w: float, odom_due: bool) -> None:
        """Publishers without templates (a controller built on publishers that take messages)."""
        if self._cmd_out_pub is not None:
            msg = self._cmd_out_msg
            _set_stamp(msg.header.stamp, time_ns)
            msg.twist.linear.x, msg.twist.angular.z = v, w
            self._cmd_out_pub.publish(msg)
        if not odom_due:
            return
        odom = self.odometry
        half = odom.heading_rad * 0.5
        qz, qw = _sin(half), _cos(half)
        x, y = odom.x_m, odom.y_m
        msg = self._odom_msg
        _set_stamp(msg.header.stamp, time_ns)
        pose = msg.pose.pose
        pose.position.x, pose.position.y = x, y
        pose.orientation.z, pose.orientation.w = qz, qw
        twist = msg.twist.twist
        twist.linear.x, twist.angular.z = odom.linear_mps, odom.angular_radps
        if self._odom_pub is not None:
            self._odom_pub.publish(msg)
        if self._tf_pub is not None:
            tf = self._tf
            _set_stamp(tf.header.stamp, time_ns)
            tf.transform.translation.x, tf.transform.translation.y = x, y
            tf.transform.rotation.z, tf.transform.rotation.w = qz, qw
            self._tf_pub.publish(self._tf_msg)


def _leaves(parent: str, *fields: str) -> list[tuple[str, str]]:
    """float64 leaves `parent.field` of a message template."""
    return [(f"{parent}.{f}", "d") for f in fields]
