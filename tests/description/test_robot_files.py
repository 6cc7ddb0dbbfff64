"""The shipped robot and world files: they load, agree with each other and with the controller's dimensions."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from diffctl.description.model import Box, Cylinder, Model, Plane, Sphere
from diffctl.description.ros2_control import gz_ros2_control_parameters, parse_ros2_control, ros2_control_blocks
from diffctl.description.sdf_loader import load, load_model, load_world
from diffctl.errors import DescriptionError

REPO = Path(__file__).resolve().parents[2]
CAR = REPO / "description" / "my_diff_car.sdf"
CAR_CONTROL = REPO / "description" / "my_diff_car_control.sdf"
WORLD = REPO / "config" / "worlds" / "empty.world"
WHEEL_SEPARATION_M = 0.3
WHEEL_RADIUS_M = 0.04
WHEEL_JOINTS = ("base_link_to_left_wheel", "base_link_to_right_wheel")


@pytest.fixture(scope="module", params=[CAR, CAR_CONTROL], ids=["plugins", "ros2_control"])
def car(request: pytest.FixtureRequest) -> Model:
    return load_model(request.param)


def _lowest_point_z(model: Model) -> float:
    lows = []
    for link in model.links:
        for c in link.collisions:
            centre = link.pose_world.compose(c.pose_link)
            g = c.geometry
            if isinstance(g, Sphere):
                lows.append(centre.xyz[2] - g.radius_m)
            elif isinstance(g, Cylinder):  # axis horizontal for the wheels
                axis = centre.rotate((0, 0, 1))
                lows.append(centre.xyz[2] - g.radius_m * math.sqrt(1 - axis[2] ** 2) - g.length_m / 2 * abs(axis[2]))
            elif isinstance(g, Box):
                lows.append(centre.xyz[2] - g.size_m[2] / 2)  # boxes are not rotated in these files
    return min(lows)


def test_car_frames_joints_and_dimensions(car: Model) -> None:
    assert car.name == "my_diff_car"
    assert car.root_link() == "base_footprint"
    assert {link.name for link in car.links} >= {
        "base_footprint",
        "base_link",
        "left_wheel",
        "right_wheel",
        "caster",
        "lidar_link",
        "imu_link",
        "camera_link",
    }
    assert car.link("base_footprint").pose_world.xyz == (0, 0, 0)
    left, right = (car.joint(n) for n in WHEEL_JOINTS)
    for j, child in ((left, "left_wheel"), (right, "right_wheel")):
        assert (j.type, j.parent, j.child) == ("continuous", "base_link", child)
        assert j.axis_world == pytest.approx((0, 1, 0))
        wheel = car.link(child)
        (collision,) = wheel.collisions
        assert isinstance(collision.geometry, Cylinder)
        assert collision.geometry.radius_m == WHEEL_RADIUS_M
        # the cylinder axis is turned onto the joint axis, and the wheel touches the ground
        assert wheel.pose_world.compose(collision.pose_link).rotate((0, 0, 1)) == pytest.approx((0, 1, 0), abs=1e-12)
        assert wheel.pose_world.xyz[2] == pytest.approx(WHEEL_RADIUS_M)
        assert collision.surface.mu >= 0.9
    assert left.pose_world.xyz[1] - right.pose_world.xyz[1] == pytest.approx(WHEEL_SEPARATION_M)
    assert left.pose_world.xyz[0] == right.pose_world.xyz[0]
    caster = car.link("caster")
    assert car.joint("caster_joint").type == "fixed"
    assert caster.collisions[0].surface.mu < 0.1
    assert caster.pose_world.xyz[0] < -0.1  # behind the axle: the car rests on three points
    assert _lowest_point_z(car) == pytest.approx(0.0, abs=1e-12)
    masses = [
        (link.inertial.mass_kg, link.pose_world.compose(link.inertial.pose_link).xyz)
        for link in car.links
        if link.inertial
    ]
    total = sum(m for m, _ in masses)
    com_z = sum(m * p[2] for m, p in masses) / total
    assert 1.0 < total < 5.0 and com_z < 0.1  # light car, low centre of mass


def test_car_sensors(car: Model) -> None:
    sensors = {s.name: s for s in car.sensors()}
    lidar, imu, camera = sensors["lidar"], sensors["imu"], sensors["camera"]
    assert (lidar.type, lidar.sdf_type, lidar.topic, lidar.update_rate_hz, lidar.link) == (
        "lidar",
        "gpu_lidar",
        "/lidar",
        10,
        "lidar_link",
    )
    assert lidar.lidar.horizontal_samples == 360
    assert (lidar.lidar.range_min_m, lidar.lidar.range_max_m) == (0.1, 10.0)
    assert lidar.lidar.horizontal_max_angle_rad - lidar.lidar.horizontal_min_angle_rad == pytest.approx(2 * math.pi)
    assert lidar.lidar.noise.active
    assert (imu.type, imu.topic, imu.update_rate_hz) == ("imu", "/imu", 100)
    assert all(n.active and n.stddev < 0.05 for n in imu.imu.angular_velocity_noise + imu.imu.linear_acceleration_noise)
    assert (camera.type, camera.topic, camera.update_rate_hz) == ("camera", "/camera", 10)
    assert (camera.camera.width_px, camera.camera.height_px) == (320, 240)
    assert camera.frame_id == "camera_link"
    # the camera sits in front of its own box, the lidar above the chassis
    assert camera.pose_world.xyz[0] > car.link("camera_link").pose_world.xyz[0] + 0.01
    assert lidar.pose_world.xyz[2] > 0.1


def test_the_two_car_files_have_identical_geometry() -> None:
    a, b = load_model(CAR), load_model(CAR_CONTROL)
    assert a.links == b.links
    assert a.joints == b.joints
    assert a.frames == b.frames


def test_plugin_variant_carries_gazebo_diff_drive_and_joint_state_publisher() -> None:
    car = load_model(CAR)
    assert car.ros2_control == ()
    dd = car.plugin("gz-sim-diff-drive-system")
    assert dd is not None and dd.name == "gz::sim::systems::DiffDrive"
    p = dd.as_dict()
    assert (p["left_joint"], p["right_joint"]) == WHEEL_JOINTS
    assert float(p["wheel_separation"]) == WHEEL_SEPARATION_M and float(p["wheel_radius"]) == WHEEL_RADIUS_M
    assert (p["topic"], p["odom_topic"], p["tf_topic"], p["frame_id"], p["child_frame_id"]) == (
        "cmd_vel",
        "odom",
        "tf",
        "odom",
        "base_footprint",
    )
    assert float(p["odom_publish_frequency"]) == 50
    assert [p.system for p in car.plugins] == ["diff-drive", "joint-state-publisher"]
    jsp = car.plugin("gz-sim-joint-state-publisher-system")
    assert jsp is not None and jsp.get("topic") == "joint_states"
    assert gz_ros2_control_parameters(car) == []


def test_control_variant_carries_the_tutorial_ros2_control_block_and_plugin() -> None:
    car = load_model(CAR_CONTROL)
    assert car.plugin("diff-drive") is None and car.plugin("joint-state-publisher") is None
    (rc,) = car.ros2_control
    assert (rc.name, rc.type, rc.hardware_plugin) == ("robot", "system", "gz_ros2_control/GazeboSimSystem")
    assert [j.name for j in rc.joints] == ["base_link_to_right_wheel", "base_link_to_left_wheel"]
    for j in rc.joints:
        assert [i.name for i in j.command_interfaces] == ["velocity"]
        assert [i.name for i in j.state_interfaces] == ["position", "velocity"]
    plugin = car.plugin("gz_ros2_control")
    assert plugin is not None and plugin.filename == "libgz_ros2_control-system"
    assert plugin.system == "gz_ros2_control"
    assert gz_ros2_control_parameters(car) == ["PARAMETERS_CONFIG_FILE_PLACEHOLDER"]
    # the same from the raw text, as the controller manager reads /robot_description
    text = CAR_CONTROL.read_text().replace("PARAMETERS_CONFIG_FILE_PLACEHOLDER", "/abs/diff_drive_controller.yaml")
    assert gz_ros2_control_parameters(text) == ["/abs/diff_drive_controller.yaml"]
    assert ros2_control_blocks(text) == [rc]


def test_empty_world() -> None:
    w = load_world(WORLD)
    assert w.name == "empty"
    assert (w.physics.max_step_size_s, w.physics.real_time_factor) == (0.001, 1.0)
    assert w.physics.gravity == (0, 0, -9.8)
    (ground,) = w.models
    assert ground.name == "ground_plane" and ground.static
    (collision,) = ground.links[0].collisions
    assert isinstance(collision.geometry, Plane) and collision.geometry.normal == (0, 0, 1)
    assert collision.surface.mu == 1.0
    (sun,) = w.lights
    assert sun.type == "directional" and sun.direction[2] < 0
    names = [p.name for p in w.plugins]
    for system in ("Physics", "UserCommands", "SceneBroadcaster", "Sensors", "Imu"):
        assert f"gz::sim::systems::{system}" in names
    assert [p.system for p in w.plugins] == ["physics", "user-commands", "scene-broadcaster", "sensors", "imu"]
    assert isinstance(load(WORLD), type(w)) and isinstance(load(CAR), Model)


def test_ros2_control_block_alone_with_parameters_and_errors() -> None:
    rc = parse_ros2_control("""<ros2_control name="mock" type="System">
      <hardware><plugin>mock_components/GenericSystem</plugin><param name="calculate_dynamics">true</param></hardware>
      <joint name="j1">
        <command_interface name="position"><param name="min">-1</param><param name="max">1</param></command_interface>
        <state_interface name="position"><param name="initial_value">0.5</param></state_interface>
        <param name="mimic">j0</param>
      </joint>
      <sensor name="imu"><state_interface name="orientation.x"/></sensor>
      <gpio name="io"><command_interface name="led"/></gpio>
    </ros2_control>""")
    assert rc.type == "system" and rc.hardware_param("calculate_dynamics") == "true"
    (j1,) = rc.joints
    assert (j1.command_interfaces[0].min, j1.command_interfaces[0].max) == (-1.0, 1.0)
    assert j1.state_interfaces[0].initial_value == 0.5 and j1.params == (("mimic", "j0"),)
    assert rc.sensors[0].state_interfaces[0].name == "orientation.x" and rc.gpios[0].name == "io"
    # ros2_control's component parser: the element's data_type attribute, double when absent
    assert [i.data_type for i in (*j1.command_interfaces, *j1.state_interfaces)] == ["double", "double"]
    flag = parse_ros2_control("""<ros2_control name="m" type="system"><hardware><plugin>p</plugin></hardware>
      <gpio name="io"><state_interface name="flag" data_type="bool"><param name="initial_value">true</param>
      </state_interface></gpio></ros2_control>""").gpios[0].state_interfaces[0]
    assert (flag.data_type, flag.initial_value) == ("bool", 1.0)
    bad = [
        ('<ros2_control name="r" type="robot"><hardware><plugin>x</plugin></hardware></ros2_control>', "type 'robot'"),
        ('<ros2_control name="r" type="system"><hardware/></ros2_control>', "Missing <plugin> tag of <hardware>"),
        (
            '<ros2_control name="r" type="system"><hardware><plugin>x</plugin></hardware>\n<joint name="a">'
            '<state_interface name="position"><param name="initial_value">zero</param></state_interface></joint>'
            "</ros2_control>",
            "'initial_value' must be a number",
        ),
        ("<ros2_control", "malformed XML"),
        (
            '<ros2_control name="r" type="system"><hardware><plugin>x</plugin></hardware>\n<gpio name="g">'
            '<state_interface name="s" data_type="float64"/></gpio></ros2_control>',
            "data_type 'float64'",
        ),
    ]
    # no <hardware> at all parses, as ros2_control's parser takes it (a xacro leaving a block empty in simulation);
    # only loading hardware of that empty plugin name fails
    empty = parse_ros2_control('<ros2_control name="imu" type="sensor">\n</ros2_control>')
    assert (empty.name, empty.hardware_plugin, empty.joints, empty.sensors) == ("imu", "", (), ())
    for text, needle in bad:
        with pytest.raises(DescriptionError) as info:
            parse_ros2_control(text, source="block.xml")
        assert needle in str(info.value) and str(info.value).startswith("block.xml"), str(info.value)
    with pytest.raises(DescriptionError, match="empty <parameters>"):
        gz_ros2_control_parameters(
            '<sdf version="1.8"><model name="m"><plugin filename="gz_ros2_control-system" '
            'name="p"><parameters/></plugin></model></sdf>'
        )
