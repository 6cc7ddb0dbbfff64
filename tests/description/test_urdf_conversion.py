"""URDF → simulated model as Gazebo's parser_urdf does it, checked against independent oracles.

Oracles: trimesh's volume integration for the mass properties of lumped links (a composite of solid boxes),
PyBullet's own URDF importer for link frames, and the names/frames Gazebo documents for lumped links.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pybullet as pb
import pytest
import trimesh

from diffctl.description.pose import Pose
from diffctl.description.robot_files import load_description, parse_description
from diffctl.description.sdf_loader import parse_model
from diffctl.description.urdf.lumping import tensor
from diffctl.description.urdf.to_model import urdf_to_sdf_text
from tests.description.description_helpers import mat_np

DATA = Path(__file__).resolve().parent / "data" / "urdf"
DENSITY = 1000.0


def _inertia_world(inertial) -> tuple[float, np.ndarray, np.ndarray]:
    """(mass, centre of mass, tensor about it in link axes) of a diffctl Inertial."""
    r = np.array(inertial.pose_link.to_matrix())[:3, :3]
    i = tensor((inertial.ixx, inertial.ixy, inertial.ixz, inertial.iyy, inertial.iyz, inertial.izz))
    return inertial.mass_kg, np.array(inertial.pose_link.xyz), r @ i @ r.T


def _fmt(values) -> str:
    return " ".join(repr(float(v)) for v in values)


def test_lumped_mass_properties_match_a_solid_composite() -> None:
    """Three solid boxes welded by rotated fixed joints: mass, centre of mass and inertia equal trimesh's."""
    # (link, joint origin xyz/rpy from its parent, box extents, box pose in the link frame)
    parts = [
        ("base", None, (0.4, 0.2, 0.1), ((0.02, -0.01, 0.03), (0.3, -0.2, 0.4))),
        ("plate", ((0.1, 0.05, 0.08), (0.5, 0.1, -0.7)), (0.12, 0.1, 0.02), ((0.01, 0.02, -0.01), (-0.4, 0.6, 0.2))),
        ("bracket", ((0.0, 0.04, 0.02), (0.0, 1.2, 0.0)), (0.05, 0.03, 0.08), ((0.0, 0.0, 0.01), (0.0, 0.0, 0.0))),
    ]
    links, joints, meshes = [], [], []
    to_base = np.eye(4)
    for i, (name, joint, extents, (xyz, rpy)) in enumerate(parts):
        box = trimesh.creation.box(extents=extents)
        box.density = DENSITY
        inertia = box.moment_inertia  # about its centre, in its own axes
        links.append(
            f'<link name="{name}"><inertial><origin xyz="{_fmt(xyz)}" rpy="{_fmt(rpy)}"/>'
            f'<mass value="{float(box.mass)!r}"/><inertia ixx="{float(inertia[0, 0])!r}" ixy="0" ixz="0" '
            f'iyy="{float(inertia[1, 1])!r}" iyz="0" izz="{float(inertia[2, 2])!r}"/></inertial></link>'
        )
        if joint is not None:
            joints.append(
                f'<joint name="j{i}" type="fixed"><parent link="{parts[i - 1][0]}"/><child link="{name}"/>'
                f'<origin xyz="{_fmt(joint[0])}" rpy="{_fmt(joint[1])}"/></joint>'
            )
            to_base = to_base @ mat_np(*joint)
        placed = box.copy()
        placed.apply_transform(to_base @ mat_np(xyz, rpy))
        meshes.append(placed)
    urdf = f'<robot name="composite">{"".join(links)}{"".join(joints)}</robot>'
    model = parse_description(urdf)
    assert [link.name for link in model.links] == ["base"]
    mass, com, inertia = _inertia_world(model.link("base").inertial)

    composite = trimesh.util.concatenate(meshes)
    composite.density = DENSITY
    assert mass == pytest.approx(composite.mass, rel=1e-9)
    assert com == pytest.approx(composite.center_mass, abs=1e-12)
    assert inertia == pytest.approx(composite.moment_inertia, rel=1e-9, abs=1e-12)
    # sdformat keeps the parent's inertial-frame orientation for the merged tensor
    assert model.link("base").inertial.pose_link.rpy == pytest.approx((0.3, -0.2, 0.4))


def test_link_frames_match_pybullets_urdf_importer() -> None:
    """The kinematic view (every URDF link) puts each link where PyBullet's importer does."""
    path = DATA / "lumped_arm.urdf"
    model = load_description(path, simulation=False)
    client = pb.connect(pb.DIRECT)
    try:
        body = pb.loadURDF(str(path), physicsClientId=client, flags=pb.URDF_USE_INERTIA_FROM_FILE)
        # The importer puts the base link frame at the origin, as the model frame is here.
        for index in range(pb.getNumJoints(body, physicsClientId=client)):
            name = pb.getJointInfo(body, index, physicsClientId=client)[12].decode()
            state = pb.getLinkState(body, index, computeForwardKinematics=True, physicsClientId=client)
            bullet = Pose(tuple(state[4]), tuple(state[5]))
            assert model.link(name).pose_model.is_close(bullet, tol=1e-6), name
    finally:
        pb.disconnect(client)


def test_diff_drive_robot_as_gazebo_spawns_it() -> None:
    model = load_description(DATA / "diff_car.urdf")
    # base_link and the caster and lidar are lumped into the massless root base_footprint, under Gazebo's names
    assert [link.name for link in model.links] == ["base_footprint", "left_wheel", "right_wheel"]
    base = model.link("base_footprint")
    assert [c.name for c in base.collisions] == [
        "base_footprint_fixed_joint_lump__base_link_collision",
        "base_footprint_fixed_joint_lump__caster_collision_1",
    ]
    assert [v.name for v in base.visuals] == [
        "base_footprint_fixed_joint_lump__base_link_visual",
        "base_footprint_fixed_joint_lump__caster_visual_1",
        "base_footprint_fixed_joint_lump__lidar_body_visual_2",
    ]
    # lumped links and joints survive as frames at their URDF poses
    frames = {f.name: f for f in model.frames}
    assert set(frames) == {"base_joint", "base_link", "caster_joint", "caster", "lidar_joint", "lidar_link"}
    assert all(f.attached_to == "base_footprint" for f in frames.values())
    assert frames["caster"].pose_model.is_close(Pose.from_xyz_rpy((-0.15, 0, 0.02), (0, 0, 0.5)), 1e-12)
    # the caster's box moved with it; its <gazebo reference> friction and material apply to its shapes only
    caster_col = base.collisions[1]
    assert caster_col.pose_link.is_close(Pose.from_xyz_rpy((-0.15, 0, 0.02), (0, 0, 0.5)), 1e-12)
    assert (caster_col.surface.mu, caster_col.surface.mu2) == (0.01, 0.02)
    assert (base.collisions[0].surface.mu, base.collisions[0].surface.mu2) == (1.0, 1.0)
    assert base.visuals[0].rgba == (0.0, 0.0, 1.0, 1.0)  # URDF material by name
    assert base.visuals[1].rgba == (0.7, 0.7, 0.7, 1.0)  # Gazebo/Grey
    assert model.link("left_wheel").collisions[0].surface.mu == 1.5
    # the lidar's sensor stays where it was written: on lidar_link, now a frame of base_footprint
    (lidar,) = base.sensors
    assert lidar.link == "base_footprint"
    assert lidar.pose_link.is_close(Pose.from_xyz_rpy((0.1, 0, 0.13), (0, 0, 1.5708)), 1e-12)
    assert lidar.topic == "/scan"
    # continuous joints become revolute without position limits; URDF limits and dynamics carry over
    left, right = model.joint("left_wheel_joint"), model.joint("right_wheel_joint")
    assert (left.type, left.parent, left.child) == ("revolute", "base_footprint", "left_wheel")
    assert not left.limits.bounded and math.isinf(left.limits.effort)
    assert (right.limits.effort, right.limits.velocity) == (10.0, 20.0)
    assert left.dynamics.damping == 0.01
    assert left.pose_world.is_close(Pose.from_xyz_rpy((0, 0.15, 0.04), (-1.5708, 0, 0)), 1e-12)
    assert model.ignored == ()


def test_plugins_and_ros2_control_reach_the_model_as_from_sdf() -> None:
    model = load_description(DATA / "diff_car.urdf")
    (plugin,) = model.plugins
    sdf = parse_model(
        '<sdf version="1.11"><model name="m"><static>true</static><link name="a"/>'
        '<plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin">'
        "<parameters>/tmp/controllers.yaml</parameters><ros><namespace>/car</namespace></ros></plugin>"
        "</model></sdf>",
        check_files=False,
    ).plugins[0]
    assert (plugin.name, plugin.filename, plugin.params, plugin.system) == (
        sdf.name,
        sdf.filename,
        sdf.params,
        "gz_ros2_control",
    )
    assert "<namespace>/car</namespace>" in plugin.xml
    (block,) = model.ros2_control
    assert block.hardware_plugin == "gz_ros2_control/GazeboSimSystem"
    left = block.joints[0]
    assert (left.command_interfaces[0].min, left.command_interfaces[0].max) == (-10.0, 10.0)
    assert left.state_interfaces[0].initial_value == 0.5


def test_kinematic_view_keeps_every_urdf_link_and_joint() -> None:
    model = load_description(DATA / "diff_car.urdf", simulation=False)
    assert {link.name for link in model.links} == {
        "base_footprint",
        "base_link",
        "caster",
        "left_wheel",
        "lidar_link",
        "right_wheel",
    }
    assert model.link("base_footprint").inertial is None
    static = (DATA / "diff_car.urdf").read_text().replace("</robot>", "<gazebo><static>true</static></gazebo></robot>")
    assert parse_description(static, simulation=False).static and parse_description(static).static
    assert {j.name: j.type for j in model.joints} == {
        "base_joint": "fixed",
        "caster_joint": "fixed",
        "left_wheel_joint": "continuous",
        "lidar_joint": "fixed",
        "right_wheel_joint": "continuous",
    }
    assert not model.static


ROBOT = '<robot name="r">{}</robot>'
MASS = '<inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>'


def _link(name: str, mass: bool = True, extra: str = "") -> str:
    return f'<link name="{name}">{MASS if mass else ""}{extra}</link>'


def _joint(name: str, kind: str, parent: str, child: str, extra: str = "") -> str:
    return f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>{extra}</joint>'


def test_preserve_fixed_joint_and_disable_lumping() -> None:
    urdf = ROBOT.format(
        _link("a")
        + _link("b")
        + _link("c")
        + _joint("kept", "fixed", "a", "b", '<origin xyz="1 0 0"/>')
        + _joint("locked", "fixed", "a", "c")
        + '<gazebo reference="kept"><preserveFixedJoint>true</preserveFixedJoint></gazebo>'
        + '<gazebo reference="locked"><disableFixedJointLumping>true</disableFixedJointLumping></gazebo>'
    )
    model = parse_description(urdf)
    assert [link.name for link in model.links] == ["a", "b", "c"]
    kept, locked = model.joint("kept"), model.joint("locked")
    assert kept.type == "fixed" and kept.pose_world.xyz == (1.0, 0.0, 0.0)
    assert locked.type == "revolute" and (locked.limits.lower, locked.limits.upper) == (0.0, 0.0)


def test_massless_link_is_dropped_with_its_subtree() -> None:
    urdf = ROBOT.format(
        _link("base")
        + _link("arm", mass=False)
        + _link("hand")
        + _joint("shoulder", "revolute", "base", "arm", '<limit lower="-1" upper="1" effort="1" velocity="1"/>')
        + _joint("wrist", "continuous", "arm", "hand")
    )
    model = parse_description(urdf)
    assert [link.name for link in model.links] == ["base"]
    assert model.joints == ()
    assert any("'arm' has no mass" in line and "not modeled" in line for line in model.ignored)
    # the tree view for TF keeps it
    assert len(parse_description(urdf, simulation=False).links) == 3


def test_world_root_pins_the_robot_and_floating_joints_make_free_links() -> None:
    urdf = ROBOT.format(
        _link("world", mass=False)
        + _link("base")
        + _link("ball")
        + _joint("pin", "fixed", "world", "base", '<origin xyz="0 0 1"/>')
        + _joint("free", "floating", "base", "ball", '<origin xyz="0 0 2"/>')
    )
    model = parse_description(urdf)
    assert [link.name for link in model.links] == ["base", "ball"]
    (pin,) = model.joints
    assert (pin.type, pin.parent, pin.child) == ("fixed", "world", "base")
    assert model.link("ball").pose_model.xyz == (0.0, 0.0, 3.0)
    assert any("'free' is floating" in line for line in model.ignored)


def test_mimic_joint_is_kept_and_reversed_limits_are_swapped() -> None:
    limit = '<limit lower="0.5" upper="-0.5" effort="1" velocity="2"/>'
    urdf = ROBOT.format(
        _link("a")
        + _link("b")
        + _link("c")
        + _joint("j1", "revolute", "a", "b", limit)
        + _joint("j2", "revolute", "a", "c", limit + '<mimic joint="j1" multiplier="-1"/>')
    )
    model = parse_description(urdf)
    assert (model.joint("j1").limits.lower, model.joint("j1").limits.upper) == (-0.5, 0.5)
    assert model.joint("j2").mimic == ("j1", -1.0, 0.0)  # simulated (sim/mimic.py), so not in model.ignored
    assert not any("mimic" in line for line in model.ignored)


def test_ros2_control_joint_lumped_away_is_skipped_as_gz_ros2_control_does() -> None:
    urdf = ROBOT.format(
        _link("a")
        + _link("b")
        + _link("c")
        + _joint("weld", "fixed", "a", "b")
        + _joint("wheel", "continuous", "a", "c")
        + '<ros2_control name="s" type="system"><hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin>'
        + '<param name="rate">100</param></hardware>'
        + '<joint name="weld"><state_interface name="position"/></joint>'
        + '<joint name="wheel"><command_interface name="velocity"/><state_interface name="position">'
        + '<param name="initial_value">0.3</param></state_interface></joint>'
        + '<sensor name="imu"><state_interface name="orientation.x"/></sensor>'
        + '<gpio name="io"><command_interface name="led"/></gpio></ros2_control>'
    )
    model = parse_description(urdf)
    (block,) = model.ros2_control
    assert [j.name for j in block.joints] == ["wheel"]
    assert block.hardware_param("rate") == "100"
    assert block.joints[0].state_interfaces[0].initial_value == 0.3
    assert [s.name for s in block.sensors] == ["imu"] and [g.name for g in block.gpios] == ["io"]
    assert any("'weld'" in line and "skipped" in line for line in model.ignored)
    # the tree view keeps the block whole (the controller manager reads it from robot_description)
    assert [j.name for j in parse_description(urdf, simulation=False).ros2_control[0].joints] == ["weld", "wheel"]


def test_meshes_resolve_by_package_file_and_relative_uris(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    prefix = tmp_path / "install"
    share = prefix / "share" / "demo_meshes"
    (share / "meshes").mkdir(parents=True)
    (prefix / "share" / "ament_index" / "resource_index" / "packages").mkdir(parents=True)
    (prefix / "share" / "ament_index" / "resource_index" / "packages" / "demo_meshes").write_text("")
    box = trimesh.creation.box(extents=(0.1, 0.2, 0.3))
    box.export(share / "meshes" / "body.stl")
    box.export(tmp_path / "wheel.obj")
    box.export(share / "meshes" / "shell.dae")
    # the same box drawn in centimetres: COLLADA's <unit> scales it back to metres, as Gazebo's loader does
    big = trimesh.creation.box(extents=(10.0, 20.0, 30.0))
    big.export(share / "meshes" / "shell_cm.dae")
    cm = (share / "meshes" / "shell_cm.dae").read_text()
    (share / "meshes" / "shell_cm.dae").write_text(cm.replace("<asset>", '<asset><unit meter="0.01" name="cm"/>', 1))
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(prefix))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    monkeypatch.chdir(tmp_path)

    def mesh(uri: str) -> str:
        return f'<visual><geometry><mesh filename="{uri}" scale="2 2 2"/></geometry></visual>'

    urdf = ROBOT.format(
        _link(
            "a",
            extra=mesh("package://demo_meshes/meshes/body.stl")
            + mesh(f"file://{tmp_path}/wheel.obj")
            + mesh("wheel.obj")
            + mesh("package://demo_meshes/meshes/shell.dae")
            + mesh("package://demo_meshes/meshes/shell_cm.dae"),
        )
    )
    (tmp_path / "r.urdf").write_text(urdf)
    visuals = load_description(tmp_path / "r.urdf").link("a").visuals
    paths = [Path(v.geometry.path) for v in visuals]
    assert paths[0] == (share / "meshes" / "body.stl").resolve()
    assert paths[1] == paths[2] == (tmp_path / "wheel.obj").resolve()
    assert paths[3].suffix == ".obj" and paths[3].is_relative_to(tmp_path / "cache")
    converted = trimesh.load(paths[3], force="mesh")
    assert converted.bounds == pytest.approx(box.bounds, abs=1e-6)  # the same shape, now readable by PyBullet
    assert trimesh.load(paths[4], force="mesh").bounds == pytest.approx(box.bounds, abs=1e-6)
    assert visuals[0].geometry.scale == (2.0, 2.0, 2.0)
    # an unindexed package found the way Gazebo finds it: <GZ_SIM_RESOURCE_PATH entry>/<package>/<path>
    (tmp_path / "models" / "loose_pkg").mkdir(parents=True)
    box.export(tmp_path / "models" / "loose_pkg" / "part.stl")
    monkeypatch.setenv("GZ_SIM_RESOURCE_PATH", str(tmp_path / "models"))
    loose = parse_description(ROBOT.format(_link("a", extra=mesh("package://loose_pkg/part.stl"))))
    assert Path(loose.link("a").visuals[0].geometry.path) == (tmp_path / "models" / "loose_pkg" / "part.stl").resolve()
    assert [v.geometry.uri for v in visuals] == [
        "package://demo_meshes/meshes/body.stl",
        f"file://{tmp_path}/wheel.obj",
        "wheel.obj",
        "package://demo_meshes/meshes/shell.dae",
        "package://demo_meshes/meshes/shell_cm.dae",
    ]


def test_sdf_text_is_what_the_sdf_loader_reads_back_to_the_same_model() -> None:
    text = (DATA / "lumped_arm.urdf").read_text()
    sdf = urdf_to_sdf_text(text)
    assert sdf.startswith('<sdf version="1.11">')
    assert parse_model(sdf) == parse_description(text)
