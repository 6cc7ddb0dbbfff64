"""The state estimation nodes' parameters, declared on the node as robot_localization declares them.

Names, types and defaults are upstream's; sensors are read as odom0, odom1, … (then pose, twist, imu) up to
the first index not set. What upstream cannot run with (a covariance that is neither 15 nor 225 numbers, a
frequency that is not positive) is one ConfigError naming the parameter and its value; a sensor's config vector
of another length than 15, which upstream runs with, is padded or cut with a warning.
"""

from __future__ import annotations

import sys
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from diffctl.errors import ConfigError
from diffctl.robot_localization.filter_base import ControlParams
from diffctl.robot_localization.state import AX, STATE_SIZE, TWIST_SIZE, default_process_noise

DBL_MAX = sys.float_info.max
SENSOR_KINDS = ("odom", "pose", "twist", "imu")


@dataclass
class SensorConfig:
    kind: str  # odom, pose, twist or imu
    name: str  # e.g. odom0
    topic: str
    update: list[bool]
    differential: bool = False
    relative: bool = False
    pose_use_child_frame: bool = False
    queue_size: int = 10
    pose_threshold: float = DBL_MAX
    twist_threshold: float = DBL_MAX
    accel_threshold: float = DBL_MAX
    remove_gravity: bool = False


@dataclass
class FilterParams:
    frequency_hz: float = 30.0
    sensor_timeout_s: float = 1.0 / 30.0
    two_d_mode: bool = False
    map_frame: str = "map"
    odom_frame: str = "odom"
    base_link_frame: str = "base_link"
    base_link_frame_output: str = "base_link"
    world_frame: str = "odom"
    publish_tf: bool = True
    publish_acceleration: bool = False
    permit_corrected_publication: bool = False
    transform_time_offset_s: float = 0.0
    transform_timeout_s: float = 0.0
    print_diagnostics: bool = False
    gravity_mps2: float = 9.80665
    predict_to_current_time: bool = False
    smooth_lagged_data: bool = False
    history_length_s: float = 0.0
    reset_on_time_jump: bool = False
    control: ControlParams | None = None
    stamped_control: bool = False
    dynamic_process_noise_covariance: bool = False
    initial_state: np.ndarray | None = None
    disabled_at_startup: bool = False
    process_noise: np.ndarray = field(default_factory=default_process_noise)
    initial_estimate_covariance: np.ndarray = field(default_factory=lambda: np.eye(STATE_SIZE) * 1e-9)
    sensors: list[SensorConfig] = field(default_factory=list)
    infos: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)


def _typed(node: Any, name: str, type_name: str) -> Any:
    """Declare `name` statically typed with no default (upstream's rclcpp::PARAMETER_* form); its value or None."""
    from diffctl.client.parameter import Parameter

    return node.declare_parameter(name, getattr(Parameter.Type, type_name)).value


def _update_vector(node: Any, name: str, warnings: list[str]) -> list[bool]:
    """A sensor's `<name>_config`. Upstream reads whatever length is given and indexes it up to 15 (a 9-element
    IMU vector is common and runs there, its missing entries read as off): shorter vectors are padded with
    false and longer ones cut, with a warning rather than a refusal."""
    value = [bool(v) for v in node.declare_parameter(name, [False] * STATE_SIZE).value]
    if len(value) != STATE_SIZE:
        warnings.append(f"parameter {name} has {len(value)} elements, not {STATE_SIZE} (x, y, z, roll, pitch, yaw, "
                        f"vx, vy, vz, vroll, vpitch, vyaw, ax, ay, az): "
                        + ("the missing ones are taken as false" if len(value) < STATE_SIZE
                           else "the elements past the 15th are ignored"))
    return (value + [False] * STATE_SIZE)[:STATE_SIZE]


def _covariance(node: Any, name: str, infos: list[str]) -> np.ndarray | None:
    flat = _typed(node, name, "DOUBLE_ARRAY")
    if flat is None:
        return None
    values = np.array(list(flat), dtype=float)
    if values.size == STATE_SIZE:
        infos.append(f"Detected a {name} parameter with length {STATE_SIZE}. Assuming diagonal values specified.")
        return np.diag(values)
    if values.size == STATE_SIZE * STATE_SIZE:
        return values.reshape(STATE_SIZE, STATE_SIZE)
    raise ConfigError(f"Invalid {name} specified. Expected a length of {STATE_SIZE} or {STATE_SIZE * STATE_SIZE}, "
                      f"got {values.size}")


def _control(node: Any, p: FilterParams, use_control: bool, timeout_s: float) -> list[bool]:
    """use_control's vectors, with upstream's fallbacks (missing limits default, missing gains 1)."""
    if not use_control:
        return [False] * TWIST_SIZE
    update = _typed(node, "control_config", "BOOL_ARRAY")
    ok = True
    if update is None:
        p.errors.append("use_control is set to true, but control_config is missing. No control term will be used.")
        update, ok = [False] * TWIST_SIZE, False
    elif len(update) != TWIST_SIZE:
        p.errors.append(f"Control configuration must be of size {TWIST_SIZE}. Provided config was of size "
                        f"{len(update)}. No control term will be used.")
        update, ok = [False] * TWIST_SIZE, False
    acc_limits = _typed(node, "acceleration_limits", "DOUBLE_ARRAY")
    if acc_limits is None:
        p.errors.append("use_control is set to true, but acceleration_limits is missing. Will use default values.")
        acc_limits = [1.0] * TWIST_SIZE
    elif len(acc_limits) != TWIST_SIZE:
        p.errors.append(f"Acceleration configuration must be of size {TWIST_SIZE}. Provided config was of size "
                        f"{len(acc_limits)}. No control term will be used.")
        ok = False
    acc_gains = _typed(node, "acceleration_gains", "DOUBLE_ARRAY")
    if acc_gains is None:
        acc_gains = [1.0] * TWIST_SIZE
    elif len(acc_gains) != TWIST_SIZE:
        p.errors.append(f"Acceleration gain configuration must be of size {TWIST_SIZE}. Provided config was of size "
                        f"{len(acc_gains)}. All gains will be assumed to be 1.")
        acc_gains = [1.0] * TWIST_SIZE
    dec_limits = _typed(node, "deceleration_limits", "DOUBLE_ARRAY")
    if dec_limits is None:
        p.warnings.append("use_control is set to true, but no deceleration_limits specified. Will use acceleration "
                          "limits.")
        dec_limits = acc_limits
    elif len(dec_limits) != TWIST_SIZE:
        p.errors.append(f"Deceleration configuration must be of size {TWIST_SIZE}. Provided config was of size "
                        f"{len(dec_limits)}. No control term will be used.")
        ok = False
    dec_gains = _typed(node, "deceleration_gains", "DOUBLE_ARRAY")
    if dec_gains is None:
        p.warnings.append("use_control is set to true, but no deceleration_gains specified. Will use acceleration "
                          "gains.")
        dec_gains = acc_gains
    elif len(dec_gains) != TWIST_SIZE:
        p.errors.append(f"Deceleration gain configuration must be of size {TWIST_SIZE}. Provided config was of size "
                        f"{len(dec_gains)}. All gains will be assumed to be 1.")
        dec_gains = [1.0] * TWIST_SIZE
    p.stamped_control = node.declare_parameter("stamped_control", False).value
    if ok:
        p.control = ControlParams(list(update), int(timeout_s * 1e9), [float(v) for v in acc_limits],
                                  [float(v) for v in acc_gains], [float(v) for v in dec_limits],
                                  [float(v) for v in dec_gains])
    return list(update) if ok else [False] * TWIST_SIZE


def _sensors(node: Any, kind: str, p: FilterParams) -> list[SensorConfig]:
    out = []
    index = 0
    while True:
        name = f"{kind}{index}"
        index += 1
        topic = _typed(node, name, "STRING")
        if topic is None:
            return out
        s = SensorConfig(kind, name, topic, [False] * STATE_SIZE)
        declare = node.declare_parameter
        if kind in ("odom", "pose", "imu"):
            s.differential = declare(f"{name}_differential", False).value
            s.relative = declare(f"{name}_relative", False).value
            if s.relative and s.differential:
                p.errors.append(f"Both {name}_differential and {name}_relative were set to true. Using differential "
                                "mode.")
                s.relative = False
        if kind == "odom":
            s.pose_use_child_frame = declare(f"{name}_pose_use_child_frame", False).value
            s.pose_threshold = declare(f"{name}_pose_rejection_threshold", DBL_MAX).value
            s.twist_threshold = declare(f"{name}_twist_rejection_threshold", DBL_MAX).value
        elif kind == "pose":
            s.pose_threshold = declare(f"{name}_rejection_threshold", DBL_MAX).value
        elif kind == "twist":
            s.twist_threshold = declare(f"{name}_rejection_threshold", DBL_MAX).value
        else:
            s.pose_threshold = declare(f"{name}_pose_rejection_threshold", DBL_MAX).value
            s.twist_threshold = declare(f"{name}_twist_rejection_threshold", DBL_MAX).value
            s.accel_threshold = declare(f"{name}_linear_acceleration_rejection_threshold", DBL_MAX).value
            s.remove_gravity = declare(f"{name}_remove_gravitational_acceleration", False).value
        s.queue_size = declare(f"{name}_queue_size", 10).value
        if s.queue_size < 1:
            raise ConfigError(f"parameter {name}_queue_size must be at least 1, got {s.queue_size}")
        s.update = _update_vector(node, f"{name}_config", p.warnings)
        out.append(s)


def declare(node: Any) -> FilterParams:
    """Declare every parameter of a state estimation node on `node` and return their values."""
    p = FilterParams()
    d = node.declare_parameter
    p.print_diagnostics = d("print_diagnostics", False).value
    p.gravity_mps2 = d("gravitational_acceleration", 9.80665).value
    if d("debug", False).value:
        d("debug_out_file", "robot_localization_debug.txt")
    p.map_frame = d("map_frame", "map").value
    p.odom_frame = d("odom_frame", "odom").value
    p.base_link_frame = d("base_link_frame", "base_link").value
    p.base_link_frame_output = d("base_link_frame_output", p.base_link_frame).value
    p.world_frame = d("world_frame", p.odom_frame).value
    if len({p.map_frame, p.odom_frame, p.base_link_frame}) < 3 or p.base_link_frame_output in (p.map_frame,
                                                                                            p.odom_frame):
        p.errors.append("Invalid frame configuration! The values for map_frame, odom_frame, and base_link_frame "
                        "must be unique. If using a base_link_frame_output values, it must not match the map_frame "
                        "or odom_frame.")
    tf_prefix = _typed(node, "tf_prefix", "STRING")
    if tf_prefix:
        prefix = tf_prefix.strip("/")
        for attr in ("map_frame", "odom_frame", "base_link_frame", "base_link_frame_output", "world_frame"):
            setattr(p, attr, f"{prefix}/{getattr(p, attr)}")
    p.publish_tf = d("publish_tf", True).value
    p.publish_acceleration = d("publish_acceleration", False).value
    p.permit_corrected_publication = d("permit_corrected_publication", False).value
    p.transform_time_offset_s = d("transform_time_offset", 0.0).value
    p.transform_timeout_s = d("transform_timeout", 0.0).value
    p.frequency_hz = d("frequency", 30.0).value
    if not p.frequency_hz > 0.0:
        raise ConfigError(f"parameter 'frequency' must be greater than 0 Hz, got {p.frequency_hz}")
    p.predict_to_current_time = d("predict_to_current_time", False).value
    p.sensor_timeout_s = d("sensor_timeout", 1.0 / p.frequency_hz).value
    p.two_d_mode = d("two_d_mode", False).value
    p.smooth_lagged_data = d("smooth_lagged_data", False).value
    history = d("history_length", 0.0).value
    if not p.smooth_lagged_data and abs(history) > 0:
        p.errors.append(f"Filter history interval of {history} specified, but smooth_lagged_data is set to false. "
                        "Lagged data will not be smoothed.")
    if p.smooth_lagged_data and history < 0:
        p.errors.append(f"Negative history interval of {history} specified. Absolute value will be assumed.")
    p.history_length_s = abs(history)
    p.reset_on_time_jump = d("reset_on_time_jump", False).value
    use_control = d("use_control", False).value
    control_timeout = d("control_timeout", 0.0).value
    control_update = _control(node, p, use_control, control_timeout)
    p.dynamic_process_noise_covariance = d("dynamic_process_noise_covariance", False).value
    initial = _typed(node, "initial_state", "DOUBLE_ARRAY")
    if initial is not None:
        if len(initial) != STATE_SIZE:
            p.errors.append(f"Initial state must be of size {STATE_SIZE}. Provided config was of size "
                            f"{len(initial)}. The initial state will be ignored.")
        else:
            p.initial_state = np.array(list(initial), dtype=float)
    p.disabled_at_startup = d("disabled_at_startup", False).value
    for kind in SENSOR_KINDS:
        p.sensors += _sensors(node, kind, p)
    for s in p.sensors:
        if s.kind != "imu":
            continue
        # Measured linear acceleration wins over the commanded one.
        for i in range(3):
            if control_update[i] and s.update[AX + i]:
                axis = ("X", "Y", "Z")[i]
                p.errors.append(f"{axis} acceleration is being measured from IMU; {axis} velocity control input "
                                "is disabled")
                control_update[i] = False
                if p.control is not None:
                    p.control.update[i] = False
    if p.control is not None and not any(p.control.update):
        p.errors.append("use_control is set to true, but control_config has only false values. No control term "
                        "will be used.")
        p.control = None
    q = _covariance(node, "process_noise_covariance", p.infos)
    if q is not None:
        p.process_noise = q
    p0 = _covariance(node, "initial_estimate_covariance", p.infos)
    if p0 is not None:
        p.initial_estimate_covariance = p0
    return p
