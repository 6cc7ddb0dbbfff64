"""What the real nodes declare (Jazzy): controller_manager (controller_manager_parameters.yaml, its own
`overruns.print_warnings` and what it declares per controller), diff_drive_controller and
joint_state_broadcaster (their `*_parameters.yaml` through generate_parameter_library), and controller_interface's
base parameters — transcribed from ros-controls/ros2_control and ros2_controllers (branch jazzy) as the
expectations of test_declarations_live.py: name → (type, read_only, range or None, description or None to
leave the text unchecked). A range is generate_parameter_library's: `gt<>: [0.0]` starts just past 0.
"""

from __future__ import annotations

import math
import sys

INT_MAX = 2**63 - 1
DBL_MAX = sys.float_info.max
ABOVE_ZERO = (math.nextafter(0.0, 1.0), DBL_MAX)

# rclcpp declares these on every node (with /parameter_events' QoS overrides read-only).
RCLCPP_NODE = {
    "use_sim_time": ("bool", False, None, None),
    "start_type_description_service": ("bool", True, None, None),
    **{f"qos_overrides./parameter_events.publisher.{p}": (t, True, None, None)
       for p, t in (("depth", "integer"), ("durability", "string"), ("history", "string"),
                    ("reliability", "string"))},
}

_DIAGNOSTICS = {
    f"diagnostics.threshold.{s}.{k}.{stat}.{lvl}": ("double", False, ABOVE_ZERO, None)
    for s, kinds in (("controller_manager", ("periodicity",)),
                     ("controllers", ("periodicity", "execution_time")),
                     ("hardware_components", ("periodicity", "execution_time")))
    for k in kinds for stat in ("mean_error", "standard_deviation") for lvl in ("warn", "error")
}

MANAGER = {
    "update_rate": ("integer", True, (1, INT_MAX),
                    "The frequency of controller manager's real-time update loop. This loop reads states from "
                    "hardware, updates controllers and writes commands to hardware."),
    "enforce_command_limits": ("bool", True, None, None),
    "handle_exceptions": ("bool", True, None, None),
    "hardware_components_initial_state.unconfigured": ("string_array", False, None, None),
    "hardware_components_initial_state.inactive": ("string_array", False, None, None),
    "hardware_components_initial_state.shutdown_on_initial_state_failure": ("bool", True, None, None),
    "defaults.switch_controller.strictness": (
        "string", False, None,
        "The default switch controller strategy. This strategy is used when no strategy is specified in the "
        "switch_controller service call."),
    "defaults.allow_controller_activation_with_inactive_hardware": ("bool", True, None, None),
    "defaults.deactivate_controllers_on_hardware_self_deactivate": ("bool", True, None, None),
    **_DIAGNOSTICS,
    "overruns.print_warnings": (
        "bool", False, None,
        "If true, the controller manager will print a warning message to the console if an overrun is detected "
        "in its real-time loop (read, update and write). By default, it is set to true, except when used with "
        "use_sim_time parameter set to true."),
}
# What load_controller declares for each controller it loads.
PER_CONTROLLER = {"fallback_controllers": "string_array", "node_options_args": "string_array"}

CONTROLLER_BASE = {
    "update_rate": ("integer", False, None, ""),
    "is_async": ("bool", False, None, ""),
    "thread_priority": ("integer", False, None, ""),
}

_LIMITS = ("max_velocity", "min_velocity", "max_acceleration", "max_deceleration", "min_acceleration",
           "max_acceleration_reverse", "max_deceleration_reverse", "max_jerk", "min_jerk")
DIFF_DRIVE = {
    "left_wheel_names": ("string_array", False, None, "Names of the left side wheels' joints"),
    "right_wheel_names": ("string_array", False, None, "Names of the right side wheels' joints"),
    "wheel_separation": ("double", False, ABOVE_ZERO,
                         "Shortest distance between the left and right wheels. If this parameter is wrong, the "
                         "robot will not behave correctly in curves."),
    "wheel_radius": ("double", False, ABOVE_ZERO, None),
    "wheel_separation_multiplier": ("double", False, None, None),
    "left_wheel_radius_multiplier": ("double", False, None, None),
    "right_wheel_radius_multiplier": ("double", False, None, None),
    "tf_frame_prefix_enable": ("bool", False, None, "Enables or disables appending tf_prefix to tf frame id's."),
    "tf_frame_prefix": ("string", False, None, None),
    "odom_frame_id": ("string", False, None, None),
    "base_frame_id": ("string", False, None,
                      "Name of the robot's base frame that is child of the odometry frame."),
    "pose_covariance_diagonal": ("double_array", False, None, None),
    "twist_covariance_diagonal": ("double_array", False, None, None),
    "open_loop": ("bool", False, None, None),
    "position_feedback": ("bool", False, None, "Is there position feedback from hardware."),
    "enable_odom_tf": ("bool", False, None, None),
    "cmd_vel_timeout": ("double", False, None,
                        "Timeout in seconds after which a command received on the ``cmd_vel`` topic is considered "
                        "stale. A value of 0.0 disables the timeout."),
    "publish_limited_velocity": ("bool", False, None, "Publish limited velocity value."),
    "velocity_rolling_window_size": ("integer", False, None, None),
    "publish_rate": ("double", False, None, "Publishing rate (Hz) of the odometry and TF messages."),
    **{f"{axis}.{flag}": ("bool", False, None, "deprecated, set the respective limits to ``.NAN`` for deactivation")
       for axis in ("linear.x", "angular.z")
       for flag in ("has_velocity_limits", "has_acceleration_limits", "has_jerk_limits")},
    **{f"{axis}.{name}": ("double", False, None, None) for axis in ("linear.x", "angular.z") for name in _LIMITS},
    "linear.x.max_velocity": ("double", False, None, ""),
    "angular.z.max_deceleration": ("double", False, None, "Maximum deceleration in positive direction."),
}

JOINT_STATE_BROADCASTER = {
    "use_local_topics": ("bool", True, None, None),
    "joints": ("string_array", True, None, None),
    "extra_joints": ("string_array", True, None,
                     "Names of extra joints to be added to ``joint_states`` and ``dynamic_joint_states`` with state "
                     "set to 0."),
    "interfaces": ("string_array", True, None, None),
    "map_interface_to_joint_state.position": ("string", True, None, ""),
    "map_interface_to_joint_state.velocity": ("string", True, None, ""),
    "map_interface_to_joint_state.effort": ("string", True, None, ""),
    "use_urdf_to_filter": ("bool", True, None, None),
    "frame_id": ("string", True, None,
                 "The frame_id to be used in the published joint states. This parameter allows rviz2 to visualize "
                 "the effort of the joints."),
    "publish_dynamic_joint_states": ("bool", True, None, "Whether to publish dynamic joint states."),
}
