"""ekf_node and ukf_node: robot_localization's state estimation node on diffctl's client Node.

Subscribes to the configured odomN/poseN/twistN/imuN topics (sensor-data QoS, `<sensor>_queue_size` deep),
set_pose and (use_control) cmd_vel; publishes odometry/filtered, accel/filtered (publish_acceleration),
/diagnostics (print_diagnostics) and the world_frame→base_link transform (odom→base_link, or map→odom
through the odom→base_link another node publishes); serves set_pose, enable, reset and toggle. Every
`frequency` Hz of the node's clock (sim time with use_sim_time) the queued measurements are fused and
the state is published, stamped with the time of the last measurement.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from diffctl.interfaces import get_interface as msg
from diffctl.robot_localization import params as params_mod
from diffctl.robot_localization.estimator import Estimator
from diffctl.robot_localization.filter_base import FilterBase, Measurement
from diffctl.robot_localization.measurements import Prepared, Preparer
from diffctl.robot_localization.params import FilterParams, SensorConfig
from diffctl.robot_localization.ros_messages import (
    TfTree,
    quat_of,
    stamp_ns,
    time_msg,
    transform_msg,
    xyz_of,
)
from diffctl.robot_localization.rotations import Rigid, quat_from_rpy
from diffctl.robot_localization.state import AX, POSE_SIZE, ROLL, STATE_SIZE, VROLL, VX, X

OK, WARN, ERROR = 0, 1, 2


def _split(update: list[bool], keep: range | tuple[range, ...]) -> list[bool]:
    """`update` with only the indices in `keep` left on."""
    ranges = keep if isinstance(keep, tuple) else (keep,)
    return [u and any(i in r for r in ranges) for i, u in enumerate(update)]


class StateEstimation:
    """The callbacks of one state estimation node around its filter."""

    def __init__(self, node: Any, p: FilterParams, filt: FilterBase) -> None:
        from diffctl.client.qos import QoSProfile, ReliabilityPolicy
        from diffctl.client.qos_overriding_options import QoSOverridingOptions

        self.node, self.p, self.log = node, p, node.get_logger()
        self.clock = node.get_clock()
        self.filter = filt
        self.estimator = Estimator(filt, smooth_lagged_data=p.smooth_lagged_data,
                                   history_length_ns=int(p.history_length_s * 1e9),
                                   predict_to_current_time=p.predict_to_current_time)
        self.tf = TfTree(node)
        self.preparer = Preparer(base_link=p.base_link_frame, world_frame=p.world_frame, two_d_mode=p.two_d_mode,
                                 gravity_mps2=p.gravity_mps2, lookup=self.tf.lookup,
                                 warn=self._warn_dynamic if p.print_diagnostics else None)
        self.static_diag: dict[str, str] = {}
        self.dynamic_diag: dict[str, str] = {}
        self.static_level = self.dynamic_level = OK
        self.last_message_ns: dict[str, int] = {}
        self.last_set_pose_ns = 0
        self.last_published_ns = 0
        self.last_diag_ns = 0
        self.last_cycle_ns = 0
        self.enabled = not p.disabled_at_startup
        self.toggled_on = True
        self._told_disabled = False
        self.latest_control = np.zeros(6)
        self.latest_control_ns = 0
        for text in p.infos:
            self.log.info(text)
        for text in p.warnings:
            self.log.warning(text)
        for text in p.errors:
            self.log.error(text)
        if p.world_frame not in (p.map_frame, p.odom_frame):
            self.log.error(f"world_frame is {p.world_frame!r}: it must be the map_frame ({p.map_frame!r}) or the "
                           f"odom_frame ({p.odom_frame!r})")

        filt.control = p.control
        filt.use_dynamic_process_noise = p.dynamic_process_noise_covariance
        self.reset_filter()
        if p.initial_state is not None:
            filt.state = p.initial_state.copy()

        qos1 = QoSProfile(depth=1)
        pwcs = msg("geometry_msgs/msg/PoseWithCovarianceStamped")
        node.create_subscription(pwcs, "set_pose", self.on_set_pose, qos1)
        node.create_service(msg("robot_localization/srv/SetPose"), "set_pose", self.on_set_pose_service)
        self.enable_service = node.create_service(msg("std_srvs/srv/Empty"), "enable", self.on_enable)
        node.create_service(msg("std_srvs/srv/Empty"), "reset", self.on_reset)
        node.create_service(msg("robot_localization/srv/ToggleFilterProcessing"), "toggle", self.on_toggle)
        self.filter.last_measurement_ns = self.clock.now_ns()

        for s in p.sensors:
            self._subscribe(s, QoSProfile(depth=s.queue_size, reliability=ReliabilityPolicy.BEST_EFFORT))
        if p.control is not None:
            if p.stamped_control:
                node.create_subscription(msg("geometry_msgs/msg/TwistStamped"), "cmd_vel", self.on_control_stamped,
                                         qos1)
            else:
                node.create_subscription(msg("geometry_msgs/msg/Twist"), "cmd_vel", self.on_control, qos1)

        overrides = QoSOverridingOptions.with_default_policies()
        self.odom_pub = node.create_publisher(msg("nav_msgs/msg/Odometry"), "odometry/filtered", QoSProfile(depth=10),
                                              qos_overriding_options=overrides)
        self.accel_pub = node.create_publisher(msg("geometry_msgs/msg/AccelWithCovarianceStamped"), "accel/filtered",
                                               QoSProfile(depth=10), qos_overriding_options=overrides) \
            if p.publish_acceleration else None
        self.tf_pub = node.create_publisher(msg("tf2_msgs/msg/TFMessage"), "/tf", QoSProfile(depth=100))
        self.diag_pub = node.create_publisher(msg("diagnostic_msgs/msg/DiagnosticArray"), "/diagnostics",
                                              QoSProfile(depth=10)) if p.print_diagnostics else None
        self.published_stamps: list[int] = []
        node.create_timer(1.0 / p.frequency_hz, self.periodic_update)

    # --- subscriptions ----------------------------------------------------------------------------------------
    def _subscribe(self, s: SensorConfig, qos: Any) -> None:
        pose, twist, accel = range(X, VX), range(VX, AX), range(AX, STATE_SIZE)
        node = self.node
        if s.kind == "odom":
            pu, tu = _split(s.update, (pose, accel)), _split(s.update, (twist, accel))
            if not any(pu) and not any(tu):
                self._static(WARN, f"{s.topic}_configuration",
                             f"{s.topic} is listed as an input topic, but all update variables are false")
                return
            node.create_subscription(msg("nav_msgs/msg/Odometry"), s.topic,
                                     lambda m: self.on_odometry(m, s, pu, tu), qos)
        elif s.kind == "pose":
            pu = _split(s.update, pose)
            if not any(pu):
                self.log.error(f"Warning: {s.topic} is listed as an input topic, but all pose update variables are "
                               "false")
                return
            node.create_subscription(msg("geometry_msgs/msg/PoseWithCovarianceStamped"), s.topic,
                                     lambda m: self.on_pose(m.header, m.pose, s.name, s, pu, self.p.world_frame,
                                                            self.p.base_link_frame, False, s.pose_threshold), qos)
        elif s.kind == "twist":
            tu = _split(s.update, (twist, accel))
            if not any(tu):
                self.log.error(f"Warning: {s.topic} is listed as an input topic, but all twist update variables are "
                               "false")
                return
            node.create_subscription(msg("geometry_msgs/msg/TwistWithCovarianceStamped"), s.topic,
                                     lambda m: self.on_twist(m.header.stamp, m.header.frame_id, m.twist, s.name, tu,
                                                             s.twist_threshold), qos)
        else:
            if any(s.update[X:ROLL]):
                self.log.warning(f"Warning: Some position entries in parameter {s.name}_config are listed true, but "
                                 "sensor_msgs/Imu contains no information about position")
            if any(s.update[VX:VROLL]):
                self.log.warning(f"Warning: Some linear velocity entries in parameter {s.name}_config are listed "
                                 "true, but an sensor_msgs/Imu contains no information about linear velocities")
            pu, tu, au = _split(s.update, range(ROLL, VX)), _split(s.update, range(VROLL, AX)), _split(s.update,
                                                                                                      accel)
            if not (any(pu) or any(tu) or any(au)):
                self.log.error(f"Warning: {s.topic} is listed as an input topic, but all its update variables are "
                               "false")
                return
            node.create_subscription(msg("sensor_msgs/msg/Imu"), s.topic, lambda m: self.on_imu(m, s, pu, tu, au),
                                     qos)

    def _accept(self, topic: str, stamp: int) -> bool:
        """Upstream's gate: nothing from before the last reset or set_pose, nothing older than the topic's last."""
        if self.last_set_pose_ns >= stamp:
            self._warn_dynamic(f"{topic}_timestamp",
                               f"The {topic} message has a timestamp equal to or before the last filter reset, this "
                               f"message will be ignored. This may indicate an empty or bad timestamp. (message time: "
                               f"{stamp / 1e9})")
            return False
        last = self.last_message_ns.setdefault(topic, stamp)
        if last > stamp:
            self._warn_dynamic(f"{topic}_timestamp",
                               f"The {topic} message has a timestamp before that of the previous message received, "
                               f"this message will be ignored. This may indicate a bad timestamp. (message time: "
                               f"{stamp % 1_000_000_000})")
            return False
        return True

    def _enqueue(self, topic: str, stamp: int, prepared: Prepared | None, threshold: float) -> None:
        if prepared is not None:
            self.estimator.enqueue(Measurement(topic, stamp, prepared.values, prepared.covariance, prepared.update,
                                               threshold, self.latest_control.copy(), self.latest_control_ns))
        self.last_message_ns[topic] = stamp

    def on_odometry(self, m: Any, s: SensorConfig, pose_update: list[bool], twist_update: list[bool]) -> None:
        if self.last_set_pose_ns >= stamp_ns(m.header.stamp):
            return
        if any(pose_update):
            source = m.child_frame_id if s.pose_use_child_frame else self.p.base_link_frame
            self.on_pose(m.header, m.pose, f"{s.name}_pose", s, pose_update, self.p.world_frame, source, False,
                         s.pose_threshold)
        if any(twist_update):
            self.on_twist(m.header.stamp, m.child_frame_id, m.twist, f"{s.name}_twist", twist_update,
                          s.twist_threshold)

    def on_pose(self, header: Any, pose: Any, topic: str, s: SensorConfig, update: list[bool], target: str,
                source: str, imu: bool, threshold: float) -> None:
        stamp = stamp_ns(header.stamp)
        if not self._accept(topic, stamp):
            return
        prepared = self.preparer.prepare_pose(
            topic, stamp, header.frame_id, xyz_of(pose.pose.position), quat_of(pose.pose.orientation),
            pose.covariance, update, target_frame=target, source_frame=source, differential=s.differential,
            relative=s.relative, imu=imu, last_stamp_ns=self.last_message_ns[topic],
            state_angular_velocity=self.filter.state[VROLL:VROLL + 3])
        self._enqueue(topic, stamp, prepared, threshold)

    def on_twist(self, stamp_msg: Any, frame_id: str, twist: Any, topic: str, update: list[bool],
                 threshold: float) -> None:
        stamp = stamp_ns(stamp_msg)
        if not self._accept(topic, stamp):
            return
        t = twist.twist
        prepared = self.preparer.prepare_twist(topic, stamp, frame_id, np.array(xyz_of(t.linear)),
                                               np.array(xyz_of(t.angular)), twist.covariance, update,
                                               self.p.base_link_frame, self.filter.state[VROLL:VROLL + 3])
        self._enqueue(topic, stamp, prepared, threshold)

    def on_imu(self, m: Any, s: SensorConfig, pose_update: list[bool], twist_update: list[bool],
               accel_update: list[bool]) -> None:
        stamp = stamp_ns(m.header.stamp)
        if self.last_set_pose_ns >= stamp:
            self._warn_dynamic(f"{s.name}_timestamp",
                               f"The {s.name} message has a timestamp equal to or before the last filter reset, this "
                               f"message will be ignored. This may indicate an empty or bad timestamp. (message time: "
                               f"{stamp % 1_000_000_000})")
            return
        no_orientation = abs(m.orientation_covariance[0] + 1) < 1e-9
        base = self.p.base_link_frame
        if any(pose_update) and not no_orientation:
            pose = msg("geometry_msgs/msg/PoseWithCovariance")()
            pose.pose.orientation = m.orientation
            cov = np.zeros((POSE_SIZE, POSE_SIZE))
            cov[3:, 3:] = np.array(m.orientation_covariance, dtype=float).reshape(3, 3)
            pose.covariance = cov.ravel()
            self.on_pose(m.header, pose, f"{s.name}_pose", s, pose_update, base, base, True, s.pose_threshold)
        if any(twist_update) and not abs(m.angular_velocity_covariance[0] + 1) < 1e-9:
            twist = msg("geometry_msgs/msg/TwistWithCovariance")()
            twist.twist.angular = m.angular_velocity
            cov = np.zeros((POSE_SIZE, POSE_SIZE))
            cov[3:, 3:] = np.array(m.angular_velocity_covariance, dtype=float).reshape(3, 3)
            twist.covariance = cov.ravel()
            self.on_twist(m.header.stamp, m.header.frame_id, twist, f"{s.name}_twist", twist_update,
                          s.twist_threshold)
        if any(accel_update) and not abs(m.linear_acceleration_covariance[0] + 1) < 1e-9:
            topic = f"{s.name}_acceleration"
            if not self._accept(topic, stamp):
                return
            prepared = self.preparer.prepare_acceleration(
                topic, stamp, m.header.frame_id, np.array(xyz_of(m.linear_acceleration)),
                m.linear_acceleration_covariance, accel_update, base, s.relative, s.remove_gravity,
                None if no_orientation else quat_of(m.orientation), self.filter.state,
                self.estimator.angular_acceleration)
            self._enqueue(topic, stamp, prepared, s.accel_threshold)

    def on_control(self, m: Any) -> None:
        self._control(m, self.clock.now_ns(), self.p.base_link_frame)

    def on_control_stamped(self, m: Any) -> None:
        self._control(m.twist, stamp_ns(m.header.stamp), m.header.frame_id)

    def _control(self, twist: Any, stamp: int, frame: str) -> None:
        if frame not in (self.p.base_link_frame, ""):
            self.log.warning(f"Commanded velocities  must be given in the robot's body frame "
                             f"({self.p.base_link_frame}). Message frame was {frame}",
                             throttle_duration_sec=5.0)
            return
        self.latest_control = np.array((*xyz_of(twist.linear), *xyz_of(twist.angular)))
        self.latest_control_ns = stamp
        self.filter.set_control(self.latest_control, stamp)

    # --- services and set_pose ----------------------------------------------------------------------------------
    def reset_filter(self) -> None:
        f = self.filter
        control, dynamic = f.control, f.use_dynamic_process_noise
        f.reset()
        f.control, f.use_dynamic_process_noise = control, dynamic
        f.sensor_timeout_ns = int(self.p.sensor_timeout_s * 1e9)
        f.set_process_noise(self.p.process_noise)
        f.covariance = self.p.initial_estimate_covariance.copy()

    def reset(self) -> None:
        self.preparer.reset()
        self.estimator.clear_queue()
        self.estimator.clear_history()
        self.last_set_pose_ns = self.last_diag_ns = self.latest_control_ns = self.last_published_ns = 0
        self.tf.clear()
        self.last_message_ns.clear()
        self.reset_filter()

    def on_reset(self, request: Any, response: Any) -> Any:
        self.log.info("Received a request to reset filter.")
        self.reset()
        return response

    def on_toggle(self, request: Any, response: Any) -> Any:
        if request.on == self.toggled_on:
            self.log.warning("Service was called to toggle filter processing but state was already as requested.")
            response.status = False
        else:
            self.log.info(f"Toggling filter measurement filtering to {'On' if request.on else 'Off'}.")
            self.toggled_on = request.on
            response.status = True
        return response

    def on_enable(self, request: Any, response: Any) -> Any:
        name = self.node.get_name()
        if self.enabled:
            self.log.warning(f"[{name}:] Asking for enabling filter service, but the filter was already enabled! "
                             "Use param disabled_at_startup.")
        else:
            self.log.info(f"[{name}:] Enabling filter...")
            self.enabled = True
        return response

    def on_set_pose_service(self, request: Any, response: Any) -> Any:
        self.on_set_pose(request.pose)
        return response

    def on_set_pose(self, m: Any) -> None:
        self.log.info(f"Received set_pose request with value\n{_pose_yaml(m)}")
        self.preparer.reset()
        self.estimator.clear_queue()
        self.estimator.clear_history()
        self.last_set_pose_ns = stamp_ns(m.header.stamp)
        prepared = self.preparer.prepare_pose(
            "set_pose", self.last_set_pose_ns, m.header.frame_id, xyz_of(m.pose.pose.position),
            quat_of(m.pose.pose.orientation), m.pose.covariance, [True] * STATE_SIZE,
            target_frame=self.p.world_frame, source_frame=self.p.base_link_frame, differential=False,
            relative=False, imu=False, last_stamp_ns=0, state_angular_velocity=self.filter.state[VROLL:VROLL + 3])
        values = np.zeros(STATE_SIZE)
        covariance = np.eye(STATE_SIZE) * 1e-6
        if prepared is not None:
            values = prepared.values
            covariance[:POSE_SIZE, :POSE_SIZE] = prepared.covariance[:POSE_SIZE, :POSE_SIZE]
        self.estimator.set_state(values, covariance, self.clock.now_ns())

    # --- the cycle ----------------------------------------------------------------------------------------------
    def periodic_update(self) -> None:
        if not self.enabled:
            if not self._told_disabled:
                self._told_disabled = True
                self.log.info(f"Filter is disabled. To enable it call the {self.enable_service.service_name} service")
            return
        now = self.clock.now_ns()
        started = time.monotonic()
        if self.p.reset_on_time_jump and now < self.last_cycle_ns:
            self.reset()
        self.last_cycle_ns = now
        if self.toggled_on:
            self.estimator.integrate(now)
            self.estimator.differentiate(now)
        else:
            self.estimator.clear_queue()
            if self.filter.initialized:
                self.filter.last_measurement_ns = now
        corrected = False
        f = self.filter
        if f.initialized:
            odom = self.odometry_message()
            stamp = f.last_measurement_ns
            if not all(math.isfinite(v) for v in f.state[:12]):
                self.log.error("Critical Error, NaNs were detected in the output state of the filter. This was "
                               "likely due to poorly coniditioned process, noise, or sensor covariances.")
            corrected = not self.p.permit_corrected_publication and self.last_published_ns >= stamp
            if self.p.publish_tf and not corrected:
                self.publish_transform(stamp)
            self.last_published_ns = stamp
            if not corrected:
                self.odom_pub.publish(odom)
                self.published_stamps.append(now)
        if self.accel_pub is not None and not corrected and f.initialized:
            self.accel_pub.publish(self.accel_message())
        if self.diag_pub is not None and (now - self.last_diag_ns >= 1_000_000_000 or now < self.last_diag_ns):
            self.publish_diagnostics(now)
            self.last_diag_ns = now
        if self.p.smooth_lagged_data:
            self.estimator.clear_expired_history(f.last_measurement_ns - int(self.p.history_length_s * 1e9))
        # Wall time, not the node's clock: sim time running faster than real time is not a slow filter.
        elapsed = time.monotonic() - started
        if elapsed > 1.0 / self.p.frequency_hz:
            self.log.error(f"Failed to meet update rate! Took {elapsed}seconds. Try decreasing the rate, limiting "
                           "sensor output frequency, or limiting the number of sensors.")

    def odometry_message(self) -> Any:
        f, p = self.filter, self.p
        x, cov = f.state, f.covariance
        m = msg("nav_msgs/msg/Odometry")()
        m.header.stamp = time_msg(f.last_measurement_ns)
        m.header.frame_id = p.world_frame
        m.child_frame_id = p.base_link_frame_output
        pos, ori = m.pose.pose.position, m.pose.pose.orientation
        pos.x, pos.y, pos.z = float(x[0]), float(x[1]), float(x[2])
        ori.x, ori.y, ori.z, ori.w = quat_from_rpy(x[3], x[4], x[5])
        lin, ang = m.twist.twist.linear, m.twist.twist.angular
        lin.x, lin.y, lin.z = float(x[6]), float(x[7]), float(x[8])
        ang.x, ang.y, ang.z = float(x[9]), float(x[10]), float(x[11])
        m.pose.covariance = cov[:6, :6].ravel()
        m.twist.covariance = cov[6:12, 6:12].ravel()
        return m

    def accel_message(self) -> Any:
        f = self.filter
        m = msg("geometry_msgs/msg/AccelWithCovarianceStamped")()
        m.header.stamp = time_msg(f.last_measurement_ns)
        m.header.frame_id = self.p.base_link_frame_output
        lin, ang = m.accel.accel.linear, m.accel.accel.angular
        lin.x, lin.y, lin.z = (float(v) for v in f.state[AX:AX + 3])
        ang.x, ang.y, ang.z = (float(v) for v in self.estimator.angular_acceleration)
        cov = np.zeros((6, 6))
        cov[:3, :3] = f.covariance[AX:AX + 3, AX:AX + 3]
        cov[3:, 3:] = self.estimator.angular_acceleration_covariance
        m.accel.covariance = cov.ravel()
        return m

    def publish_transform(self, stamp: int) -> None:
        p, x = self.p, self.filter.state
        world_base = Rigid.from_xyz_quat((x[0], x[1], x[2]), quat_from_rpy(x[3], x[4], x[5]))
        tf_stamp = stamp + int(p.transform_time_offset_s * 1e9)
        tf_list = msg("tf2_msgs/msg/TFMessage")()
        if p.world_frame == p.odom_frame:
            tf_list.transforms = [transform_msg(tf_stamp, p.world_frame, p.base_link_frame_output, world_base)]
        elif p.world_frame == p.map_frame:
            base_odom = self.tf.lookup(p.base_link_frame, p.odom_frame, 0)
            if base_odom is None:
                self.log.error(f"Could not obtain transform from {p.odom_frame}->{p.base_link_frame}",
                               throttle_duration_sec=5.0, skip_first=True)
                return
            tf_list.transforms = [transform_msg(tf_stamp, p.map_frame, p.odom_frame, world_base * base_odom)]
        else:
            self.log.error(f"Odometry message frame_id was {p.world_frame}, expected {p.map_frame} or "
                           f"{p.odom_frame}")
            return
        self.tf_pub.publish(tf_list)

    # --- diagnostics --------------------------------------------------------------------------------------------
    def _static(self, level: int, key: str, text: str) -> None:
        self.static_diag[key] = text
        self.static_level = max(self.static_level, level)

    def _warn_dynamic(self, key: str, text: str) -> None:
        self.dynamic_diag[key] = text
        self.dynamic_level = max(self.dynamic_level, WARN)

    def publish_diagnostics(self, now: int) -> None:
        array = msg("diagnostic_msgs/msg/DiagnosticArray")()
        array.header.stamp = time_msg(now)
        status = msg("diagnostic_msgs/msg/DiagnosticStatus")()
        level = max(self.static_level, self.dynamic_level)
        status.level = bytes([level])
        status.name = f"{self.node.get_name()}: Filter diagnostic updater"
        status.hardware_id = "none"
        status.message = {OK: "Filter running normally", WARN: "Possible problem with filter configuration",
                          ERROR: "Erroneous data or settings detected for a robot_localization state estimation "
                                 "node."}.get(level, "")
        kv = msg("diagnostic_msgs/msg/KeyValue")
        status.values = [kv(key=k, value=v) for k, v in {**self.static_diag, **self.dynamic_diag}.items()]
        window = [t for t in self.published_stamps if now - t <= 1_000_000_000]
        self.published_stamps = window
        rate = msg("diagnostic_msgs/msg/DiagnosticStatus")()
        rate.name = f"{self.node.get_name()}: odometry/filtered topic status"
        rate.hardware_id = "none"
        hz = float(len(window))
        low, high = self.p.frequency_hz - 2, self.p.frequency_hz + 2
        rate.level = bytes([OK if low * 0.9 <= hz <= high * 1.1 else WARN])
        rate.message = "Desired frequency met" if rate.level == bytes([OK]) else "Frequency too low."
        rate.values = [kv(key="Events in window", value=str(len(window))),
                       kv(key="Actual frequency (Hz)", value=f"{hz:g}")]
        array.status = [status, rate]
        self.diag_pub.publish(array)
        self.dynamic_diag.clear()
        self.dynamic_level = OK


def _pose_yaml(m: Any) -> str:
    p, q = m.pose.pose.position, m.pose.pose.orientation
    return (f"header:\n  stamp:\n    sec: {m.header.stamp.sec}\n    nanosec: {m.header.stamp.nanosec}\n"
            f"  frame_id: {m.header.frame_id}\npose:\n  pose:\n    position:\n      x: {p.x}\n      y: {p.y}\n"
            f"      z: {p.z}\n    orientation:\n      x: {q.x}\n      y: {q.y}\n      z: {q.z}\n      w: {q.w}\n")


def run(kind: str) -> int:
    """Start ekf_node ("ekf") or ukf_node ("ukf") with this process's ROS arguments; spin until shut down."""
    from diffctl.client import component
    from diffctl.client.node import Node

    def make() -> Node:
        node = Node(f"{kind}_filter_node")
        if kind == "ukf":
            from diffctl.robot_localization.ukf import Ukf

            alpha = node.declare_parameter("alpha", 0.001).value
            kappa = node.declare_parameter("kappa", 0.0).value
            beta = node.declare_parameter("beta", 2.0).value
            filt: FilterBase = Ukf(alpha, kappa, beta)
        else:
            from diffctl.robot_localization.ekf import Ekf

            filt = Ekf()
        StateEstimation(node, params_mod.declare(node), filt)
        return node

    return component.run(make)
