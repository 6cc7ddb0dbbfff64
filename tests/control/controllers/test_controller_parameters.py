"""Controllers declare their parameters as ros2_controllers' YAML does (on a real client node), and a running
diff_drive_controller takes limit and timeout changes on its next update; the controller is driven directly."""

from __future__ import annotations

import math

import pytest
from controller_harness import configure, make_controller
from test_diff_drive_controller import BASE, NAME, Drive

from diffctl.client.parameter import Parameter
from diffctl.control.controllers.diff_drive import DiffDriveController
from diffctl.control.controllers.diff_drive_params import DECLS
from diffctl.control.controllers.forward_command import ForwardCommandController, JointGroupVelocityController
from diffctl.control.controllers.joint_state_broadcaster import JointStateBroadcaster
from diffctl.control.lifecycle import State
from diffctl.errors import ParameterError

pytestmark = pytest.mark.usefixtures("client_bus")
DOUBLE, INTEGER, DOUBLE_ARRAY = Parameter.Type.DOUBLE.value, Parameter.Type.INTEGER.value, 8


def set_params(node, values: dict) -> list[str | None]:
    """The node's answer to one `param set` per value: None when taken, else the reason."""
    results = node.set_parameters([Parameter(k, value=v) for k, v in values.items()])
    return [None if r.successful else r.reason for r in results]

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
    node = c.probe.node
    assert set(DECLS) == JAZZY_DIFF_DRIVE
    names = set(node.list_parameters([], 0).names)
    assert names >= JAZZY_DIFF_DRIVE | {"update_rate", "is_async", "thread_priority", "use_sim_time"}
    d = node.describe_parameter("wheel_separation")
    assert (d.type, d.read_only, d.additional_constraints) == (DOUBLE, False, "")
    assert d.description.startswith("Shortest distance between the left and right wheels.")
    # gt<>: [0.0] → the range starts just above 0, as generate_parameter_library writes it.
    assert d.floating_point_range[0].from_value == math.nextafter(0.0, 1.0)
    assert not node.describe_parameter("left_wheel_names").read_only
    assert not node.describe_parameter("velocity_rolling_window_size").integer_range  # no validation upstream
    assert node.describe_parameter("pose_covariance_diagonal").type == DOUBLE_ARRAY
    # controller_interface's own, declared without descriptors.
    rate = node.describe_parameter("update_rate")
    assert (rate.type, rate.description, rate.read_only) == (INTEGER, "", False)
    assert (node.get_parameter("update_rate").value, node.get_parameter("thread_priority").value) == (100, -100)
    # Defaults where the file gives nothing; the file's values (typed as declared) where it does.
    v = c.probe.parameter
    assert v("base_frame_id") == "base_link" and v("cmd_vel_timeout") == 0.5
    assert math.isnan(v("linear.x.max_velocity")) and v("linear.x.has_jerk_limits") is True
    assert v("wheel_separation") == 0.3 and list(v("left_wheel_names")) == ["left_wheel"]


def test_an_integer_in_the_file_is_declared_as_the_double_it_means():
    c = make_controller(DiffDriveController, NAME, {**BASE, "wheel_radius": 1, "velocity_rolling_window_size": 4.0})
    assert c.probe.parameter("wheel_radius") == 1.0 and isinstance(c.probe.parameter("wheel_radius"), float)
    assert c.probe.parameter("velocity_rolling_window_size") == 4


@pytest.mark.parametrize("limit", [0.0, 5.0])
def test_has_limits_false_disables_the_group_whatever_its_numbers(limit):
    """The deprecated `has_jerk_limits: false` wins over `max_jerk: 0.0` (or any value), as in Jazzy."""
    params = {**BASE, "linear.x.has_jerk_limits": False, "linear.x.max_jerk": limit, "linear.x.min_jerk": -limit}
    c = make_controller(DiffDriveController, NAME, params)
    assert math.isnan(c.params.linear.max_jerk) and math.isnan(c.params.linear.min_jerk)
    assert "[deprecated] has_jerk_limits parameter is deprecated" in c.probe.log.text("WARN")


def test_a_limit_changed_at_runtime_takes_effect_on_the_next_update():
    d = Drive(open_loop=True)
    d.run(0.2, v=1.0)
    assert d.wheel("left_wheel") == pytest.approx(1.0 / 0.04)
    assert set_params(d.node.node, {"linear.x.max_velocity": 0.2}) == [None]
    d.send(1.0, 0.0)
    d.step()
    assert d.wheel("left_wheel") == pytest.approx(0.2 / 0.04)
    assert d.c.params.linear.max_velocity == 0.2
    # An acceleration limit added at runtime shapes the very next step (0.5 m/s² × 10 ms).
    assert set_params(d.node.node, {"linear.x.max_acceleration": 0.5}) == [None]
    d.send(-1.0, 0.0)
    d.step()
    assert d.wheel("left_wheel") == pytest.approx((0.2 - 0.005) / 0.04)


def test_cmd_vel_timeout_changed_at_runtime():
    d = Drive(open_loop=True)
    assert set_params(d.node.node, {"cmd_vel_timeout": 0.0}) == [None]  # 0 disables the timeout
    d.send(0.1, 0.0)
    d.run(2.0)
    assert d.wheel("left_wheel") == pytest.approx(0.1 / 0.04)
    assert set_params(d.node.node, {"cmd_vel_timeout": 0.25}) == [None]
    d.run(0.02)
    assert d.wheel("left_wheel") == 0.0  # the command is 2 s old: stale under the new timeout


@pytest.mark.parametrize(
    ("change", "reason"),
    [
        ({"cmd_vel_timeout": "soon"}, "Wrong parameter type"),
        ({"cmd_vel_timeout": -1.0}, "NAME.cmd_vel_timeout: -1.0 must be ≥ 0.0"),
        ({"wheel_radius": 0.0}, "doesn't comply with floating point range"),
        ({"linear.x.max_acceleration": -1.0}, "NAME.linear.x.max_acceleration: -1.0 must be ≥ 0"),
        ({"linear.x.max_velocity": 1.0, "linear.x.min_velocity": 2.0}, "min_velocity"),
        ({"base_frame_id": "odom"}, "the frames must differ"),
    ],
)
def test_invalid_changes_are_refused_and_change_nothing(change, reason):
    d = Drive(open_loop=True)
    node = d.node.node
    before = {n: p.value for n, p in node.get_parameters_by_prefix("").items()}
    result = node.set_parameters_atomically([Parameter(k, value=v) for k, v in change.items()])
    assert not result.successful and reason.replace("NAME", NAME) in result.reason
    assert {n: p.value for n, p in node.get_parameters_by_prefix("").items()} == before
    d.run(0.1, v=1.0)
    assert d.wheel("left_wheel") == pytest.approx(1.0 / 0.04)


def test_other_parameters_apply_at_the_next_configure():
    d = Drive(open_loop=True)
    assert set_params(d.node.node, {"odom_frame_id": "world", "wheel_radius": 0.05}) == [None, None]
    assert d.c.params.odom_frame_id == "odom"
    d.c.on_deactivate(State.ACTIVE)
    d.c.on_cleanup(State.INACTIVE)
    configure(d.c)
    assert d.c.params.odom_frame_id == "world" and d.c.params.wheel_radius_m == 0.05


def test_joint_state_broadcaster_declares_its_parameters_read_only():
    c = make_controller(JointStateBroadcaster, "joint_state_broadcaster", {"extra_joints": ["caster"]})
    node = c.probe.node
    for name in ("joints", "interfaces", "extra_joints", "use_local_topics", "use_urdf_to_filter",
                 "map_interface_to_joint_state.position", "map_interface_to_joint_state.velocity",
                 "map_interface_to_joint_state.effort", "frame_id", "publish_dynamic_joint_states"):  # fmt: skip
        assert node.describe_parameter(name).read_only, name
    assert node.describe_parameter("joints").type == Parameter.Type.STRING_ARRAY.value
    assert list(c.probe.parameter("extra_joints")) == ["caster"] and list(c.probe.parameter("joints")) == []
    assert c.probe.parameter("use_urdf_to_filter") is True
    assert "read-only" in set_params(node, {"use_local_topics": True})[0]
    with pytest.raises(ParameterError, match=r"map_interface_to_joint_state\.position"):
        make_controller(JointStateBroadcaster, "jsb", {"map_interface_to_joint_state.position": ""})


def test_forward_command_controllers_declare_joints_and_interface():
    c = make_controller(ForwardCommandController, "fwd", {"joints": ["a", "b"], "interface_name": "position"})
    assert c.command_interface_configuration().names == ["a/position", "b/position"]
    assert not c.probe.node.describe_parameter("joints").read_only
    v = make_controller(JointGroupVelocityController, "vel", {"joints": ["a"]})
    assert v.probe.parameter("interface_name") == "velocity"
    with pytest.raises(ParameterError, match=r"fwd\.interface_name"):
        make_controller(ForwardCommandController, "fwd", {"joints": ["a"]})
