"""Controllers declare their parameters as ros2_controllers' YAML does, and a running diff_drive_controller
takes limit and timeout changes on its next update. The node's parameters are the bus's ParameterStore (the
bookkeeping behind the parameter services); the controller is driven directly."""

from __future__ import annotations

import math

import pytest
from controller_fakes import make_controller
from test_diff_drive_controller import BASE, NAME, Drive

from diffctl.control.controllers.diff_drive import DiffDriveController
from diffctl.control.controllers.diff_drive_params import DECLS
from diffctl.control.controllers.forward_command import ForwardCommandController, JointGroupVelocityController
from diffctl.control.controllers.joint_state_broadcaster import JointStateBroadcaster
from diffctl.control.controllers.param_decl import BASE_DECLS
from diffctl.errors import ParameterError

# The Jazzy diff_drive_controller_parameter.yaml, as ROS users' files name its parameters.
JAZZY_DIFF_DRIVE = {
    "left_wheel_names", "right_wheel_names", "wheel_separation", "wheel_radius", "wheel_separation_multiplier",
    "left_wheel_radius_multiplier", "right_wheel_radius_multiplier", "tf_frame_prefix_enable", "tf_frame_prefix",
    "odom_frame_id", "base_frame_id", "pose_covariance_diagonal", "twist_covariance_diagonal", "open_loop",
    "position_feedback", "enable_odom_tf", "cmd_vel_timeout", "publish_limited_velocity",
    "velocity_rolling_window_size", "publish_rate",
    *(
        f"{axis}.{name}"
        for axis in ("linear.x", "angular.z")
        for name in (
            "has_velocity_limits", "has_acceleration_limits", "has_jerk_limits", "max_velocity", "min_velocity",
            "max_acceleration", "max_deceleration", "max_acceleration_reverse", "max_deceleration_reverse",
            "max_jerk", "min_jerk", "min_acceleration",
        )
    ),
}  # fmt: skip


def test_every_jazzy_parameter_is_declared_with_its_type_default_and_descriptor():
    c = make_controller(DiffDriveController, NAME, dict(BASE))
    store = c.node.parameters
    assert set(DECLS) == JAZZY_DIFF_DRIVE | {d.name for d in BASE_DECLS}
    assert set(store.names()) >= JAZZY_DIFF_DRIVE
    d = store.descriptor("wheel_separation")
    assert (d.type, d.read_only, d.additional_constraints) == ("double", True, "gt<>: [0.0]")
    assert store.descriptor("left_wheel_names").read_only and store.descriptor("wheel_radius").read_only
    assert not store.descriptor("linear.x.max_velocity").read_only
    assert store.descriptor("velocity_rolling_window_size").integer_range == (1, 100_000, 0)
    assert store.descriptor("cmd_vel_timeout").floating_point_range[0] == 0.0
    assert store.descriptor("publish_rate").type == "double"
    assert store.descriptor("pose_covariance_diagonal").type == "double_array"
    # Defaults where the file gives nothing; the file's values (typed as declared) where it does.
    assert store.get("base_frame_id") == "base_link" and store.get("cmd_vel_timeout") == 0.5
    assert math.isnan(store.get("linear.x.max_velocity")) and store.get("linear.x.has_jerk_limits") is True
    assert store.get("wheel_separation") == 0.3 and store.get("left_wheel_names") == ["left_wheel"]


def test_an_integer_in_the_file_is_declared_as_the_double_it_means():
    c = make_controller(DiffDriveController, NAME, {**BASE, "wheel_radius": 1, "velocity_rolling_window_size": 4.0})
    assert c.node.get_parameter("wheel_radius") == 1.0 and isinstance(c.node.get_parameter("wheel_radius"), float)
    assert c.node.get_parameter("velocity_rolling_window_size") == 4


@pytest.mark.parametrize("limit", [0.0, 5.0, -3.0])
def test_has_limits_false_disables_the_group_whatever_its_numbers(limit):
    """The deprecated `has_jerk_limits: false` wins over `max_jerk: 0.0` (or any value), as in Jazzy."""
    params = {**BASE, "linear.x.has_jerk_limits": False, "linear.x.max_jerk": limit, "linear.x.min_jerk": -limit}
    c = make_controller(DiffDriveController, NAME, params)
    assert math.isnan(c.params.linear.max_jerk) and math.isnan(c.params.linear.min_jerk)
    assert "[deprecated] has_jerk_limits parameter is deprecated" in c.node.log.text("WARN")


def test_a_limit_changed_at_runtime_takes_effect_on_the_next_update():
    d = Drive(open_loop=True)
    d.run(0.2, v=1.0)
    assert d.wheel("left_wheel") == pytest.approx(1.0 / 0.04)
    assert d.node.set_parameters({"linear.x.max_velocity": 0.2}) == [None]
    d.send(1.0, 0.0)
    d.step()
    assert d.wheel("left_wheel") == pytest.approx(0.2 / 0.04)
    assert d.c.params.linear.max_velocity == 0.2
    # An acceleration limit added at runtime shapes the very next step (0.5 m/s² × 10 ms).
    assert d.node.set_parameters({"linear.x.max_acceleration": 0.5}) == [None]
    d.send(-1.0, 0.0)
    d.step()
    assert d.wheel("left_wheel") == pytest.approx((0.2 - 0.005) / 0.04)


def test_cmd_vel_timeout_changed_at_runtime():
    d = Drive(open_loop=True)
    assert d.node.set_parameters({"cmd_vel_timeout": 0.0}) == [None]  # 0 disables the timeout
    d.send(0.1, 0.0)
    d.run(2.0)
    assert d.wheel("left_wheel") == pytest.approx(0.1 / 0.04)
    assert d.node.set_parameters({"cmd_vel_timeout": 0.25}) == [None]
    d.run(0.02)
    assert d.wheel("left_wheel") == 0.0  # the command is 2 s old: stale under the new timeout


@pytest.mark.parametrize(
    ("change", "reason"),
    [
        ({"wheel_radius": 0.5}, "read-only"),
        ({"left_wheel_names": ["x"]}, "read-only"),
        ({"cmd_vel_timeout": "soon"}, "Wrong parameter type"),
        ({"cmd_vel_timeout": -1.0}, "doesn't comply with floating point range"),
        ({"linear.x.max_acceleration": -1.0}, "NAME.linear.x.max_acceleration: -1.0 must be ≥ 0"),
        ({"linear.x.max_velocity": 1.0, "linear.x.min_velocity": 2.0}, "min_velocity"),
        ({"base_frame_id": "odom"}, "the frames must differ"),
    ],
)
def test_read_only_and_invalid_changes_are_refused_and_change_nothing(change, reason):
    d = Drive(open_loop=True)
    before = dict(d.node.params)
    refusal = d.node.parameters.set_atomically(change)
    assert refusal is not None and reason.replace("NAME", NAME) in refusal
    assert d.node.params == before
    d.run(0.1, v=1.0)
    assert d.wheel("left_wheel") == pytest.approx(1.0 / 0.04)


def test_other_parameters_apply_at_the_next_configure():
    d = Drive(open_loop=True)
    assert d.node.set_parameters({"odom_frame_id": "world"}) == [None]
    assert d.c.params.odom_frame_id == "odom"
    d.c.on_deactivate()
    d.c.on_configure()
    assert d.c.params.odom_frame_id == "world"


def test_joint_state_broadcaster_declares_its_parameters_read_only():
    c = make_controller(JointStateBroadcaster, "joint_state_broadcaster", {"extra_joints": ["caster"]})
    store = c.node.parameters
    for name in ("joints", "interfaces", "extra_joints", "use_local_topics", "use_urdf_to_filter",
                 "map_interface_to_joint_state.position", "map_interface_to_joint_state.velocity",
                 "map_interface_to_joint_state.effort"):  # fmt: skip
        assert store.descriptor(name).read_only, name
    assert store.get("extra_joints") == ["caster"] and store.get("use_urdf_to_filter") is True
    assert "read-only" in c.node.set_parameters({"use_local_topics": True})[0]
    with pytest.raises(ParameterError, match=r"map_interface_to_joint_state\.position"):
        make_controller(JointStateBroadcaster, "jsb", {"map_interface_to_joint_state.position": ""})


def test_forward_command_controllers_declare_joints_and_interface():
    c = make_controller(ForwardCommandController, "fwd", {"joints": ["a", "b"], "interface_name": "position"})
    assert c.command_interface_configuration().names == ["a/position", "b/position"]
    assert c.node.parameters.descriptor("joints").read_only
    v = make_controller(JointGroupVelocityController, "vel", {"joints": ["a"]})
    assert v.node.get_parameter("interface_name") == "velocity"
    with pytest.raises(ParameterError, match=r"fwd\.interface_name"):
        make_controller(ForwardCommandController, "fwd", {"joints": ["a"]})
