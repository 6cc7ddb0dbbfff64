"""SDF 1.7+ frame semantics: relative_to chains, <frame>, __model__, nested models, includes, placement frames.

Expected poses are worked out by hand in the model frame and carried to the world frame with an independent
numpy matrix, then compared with the loader's resolved poses to 1e-9.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from description_helpers import mat_np

from diffctl.description.model import Mesh
from diffctl.description.pose import Pose
from diffctl.description.sdf_loader import load_world, parse_model

H = math.pi / 2
TOL = 1e-9

CHAIN = """<?xml version="1.0"?>
<sdf version="1.9">
  <model name="outer">
    <static>true</static>
    <pose>1 2 0 0 0 1.5707963267948966</pose>
    <frame name="F1"><pose>1 0 0 0 0 0</pose></frame>
    <frame name="F2" attached_to="F1"><pose relative_to="F1">0 1 0 0 0 1.5707963267948966</pose></frame>
    <link name="L1"><pose relative_to="F2">1 0 0 0 0 0</pose></link>
    <link name="L2"><pose relative_to="__model__">0 0 1 0 0 0</pose></link>
    <joint name="J" type="revolute">
      <pose>0 0 0.5 0 0 0</pose>
      <parent>L2</parent><child>L1</child>
      <axis><xyz expressed_in="__model__">1 0 0</xyz></axis>
    </joint>
    <link name="L3"><pose relative_to="J">0 0 1 0 0 0</pose></link>
    <model name="inner">
      <pose relative_to="L2">0 0 1 0 0 0</pose>
      <link name="base"><pose>1 0 0 0 0 0</pose></link>
      <frame name="tip" attached_to="base"><pose relative_to="base">0 0 1 0 0 0</pose></frame>
      <link name="arm"><pose relative_to="tip">1 0 0 0 1.5707963267948966 0</pose></link>
      <model name="deep">
        <pose relative_to="arm">0 0 1 0 0 0</pose>
        <link name="x"/>
      </model>
    </model>
    <link name="L4"><pose relative_to="inner::tip">0 1 0 0 0 0</pose></link>
    <joint name="J2" type="prismatic">
      <parent>inner::arm</parent><child>L4</child>
      <axis><xyz>0 0 2</xyz></axis>
    </joint>
  </model>
</sdf>
"""

# name → (xyz, rpy) in the model frame, by hand
EXPECTED_MODEL = {
    "L1": ((1, 2, 0), (0, 0, H)),
    "L2": ((0, 0, 1), (0, 0, 0)),
    "L3": ((1, 2, 1.5), (0, 0, H)),
    "inner::base": ((1, 0, 2), (0, 0, 0)),
    "inner::arm": ((2, 0, 3), (0, H, 0)),
    "inner::deep::x": ((3, 0, 3), (0, H, 0)),
    "L4": ((1, 1, 3), (0, 0, 0)),
}
MODEL_WORLD = mat_np((1, 2, 0), (0, 0, H))


def assert_pose(actual: Pose, expected: np.ndarray) -> None:
    assert np.allclose(actual.to_matrix(), expected, atol=TOL), f"{actual} != \n{expected}"


def test_relative_to_chains_frames_and_nested_models_resolve_to_world() -> None:
    m = parse_model(CHAIN)
    assert {link.name for link in m.links} == set(EXPECTED_MODEL)
    for name, (xyz, rpy) in EXPECTED_MODEL.items():
        link = m.link(name)
        assert_pose(link.pose_model, mat_np(xyz, rpy))
        assert_pose(link.pose_world, MODEL_WORLD @ mat_np(xyz, rpy))
    assert_pose(m.pose_world, MODEL_WORLD)
    assert m.canonical_link == "L1"
    # frames: attached_to follows chains to a link; nested models appear as frames too
    tip = m.frame("inner::tip")
    assert tip.attached_to == "inner::base"
    assert_pose(tip.pose_world, MODEL_WORLD @ mat_np((1, 0, 3), (0, 0, 0)))
    assert m.frame("F2").attached_to == "L1"  # F1 hangs on __model__, i.e. the canonical link
    assert m.frame("inner").attached_to == "inner::base"
    assert_pose(m.frame("inner::deep").pose_model, mat_np((3, 0, 3), (0, H, 0)))


def test_joint_pose_is_in_the_child_frame_and_axes_are_resolved() -> None:
    m = parse_model(CHAIN)
    j = m.joint("J")
    assert (j.parent, j.child) == ("L2", "L1")
    assert_pose(j.pose_child, mat_np((0, 0, 0.5), (0, 0, 0)))
    assert_pose(j.pose_world, MODEL_WORLD @ mat_np((1, 2, 0.5), (0, 0, H)))
    # axis given in the model frame: +x of the model is +y of the world and -y of L1 (yawed 90°)
    assert np.allclose(j.axis_world, (0, 1, 0), atol=TOL)
    assert np.allclose(j.axis_child, (0, -1, 0), atol=TOL)
    j2 = m.joint("J2")
    assert (j2.parent, j2.child, j2.type) == ("inner::arm", "L4", "prismatic")
    assert np.allclose(j2.axis_child, (0, 0, 1), atol=TOL)  # normalized, in the joint (= child) frame
    assert np.allclose(j2.axis_world, (0, 0, 1), atol=TOL)


def test_sdf_1_6_axis_in_parent_model_frame() -> None:
    text = """<sdf version="1.6"><model name="m"><static>true</static>
      <link name="a"/>
      <link name="b"><pose>0 0 1 0 0 1.5707963267948966</pose></link>
      <joint name="j" type="revolute"><parent>a</parent><child>b</child>
        <axis><xyz>1 0 0</xyz><use_parent_model_frame>true</use_parent_model_frame></axis></joint>
    </model></sdf>"""
    j = parse_model(text).joint("j")
    assert np.allclose(j.axis_world, (1, 0, 0), atol=TOL)
    assert np.allclose(j.axis_child, (0, -1, 0), atol=TOL)


def test_pose_formats_degrees_and_quaternions() -> None:
    text = """<sdf version="1.9"><model name="m"><static>true</static>
      <link name="a"><pose degrees="true">1 2 3 0 0 90</pose></link>
      <link name="b"><pose rotation_format="quat_xyzw">0 0 0 0 0 0.7071067811865476 0.7071067811865476</pose></link>
    </model></sdf>"""
    m = parse_model(text)
    assert_pose(m.link("a").pose_model, mat_np((1, 2, 3), (0, 0, H)))
    assert_pose(m.link("b").pose_model, mat_np((0, 0, 0), (0, 0, H)))


def _write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


WHEEL = """<?xml version="1.0"?><sdf version="1.8"><model name="wheel">
  <link name="hub"><pose>0 0 0.1 0 0 0</pose>
    <inertial><mass>0.5</mass></inertial>
    <visual name="v"><geometry><mesh><uri>meshes/hub.stl</uri><scale>2 2 2</scale></mesh></geometry></visual>
  </link>
  <frame name="mount" attached_to="hub"><pose>0 0 -0.1 0 0 0</pose></frame>
</model></sdf>"""


def test_includes_model_uri_relative_uri_placement_frame_and_world_relative_to(tmp_path: Path) -> None:
    models = tmp_path / "models"
    _write(
        models / "wheel" / "model.config",
        "<?xml version='1.0'?><model><name>wheel</name><sdf version='1.8'>wheel.sdf</sdf></model>",
    )
    _write(models / "wheel" / "wheel.sdf", WHEEL)
    hub = _write(models / "wheel" / "meshes" / "hub.stl", "")
    hub.write_bytes(bytes(80) + (1).to_bytes(4, "little") + bytes(50))  # one (flat) triangle: binary STL
    _write(
        tmp_path / "parts" / "crate.sdf",
        """<sdf version="1.7"><model name="crate"><static>true</static>
      <link name="body"><collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision></link>
    </model></sdf>""",
    )
    world = _write(
        tmp_path / "worlds" / "w.sdf",
        """<?xml version="1.0"?>
<sdf version="1.8"><world name="w">
  <frame name="spot"><pose>10 0 0 0 0 1.5707963267948966</pose></frame>
  <include><uri>model://wheel</uri><name>front_wheel</name><pose relative_to="spot">1 0 0 0 0 0</pose></include>
  <include><uri>../parts/crate.sdf</uri><pose>0 5 0 0 0 0</pose><placement_frame>body</placement_frame></include>
  <model name="car">
    <pose relative_to="front_wheel">0 0 1 0 0 0</pose>
    <link name="chassis"><inertial><mass>2</mass></inertial></link>
    <include><uri>model://wheel</uri><name>w1</name><pose>0 0.3 0 0 0 0</pose>
      <placement_frame>mount</placement_frame></include>
    <joint name="axle" type="continuous"><parent>chassis</parent><child>w1::hub</child>
      <axis><xyz>0 1 0</xyz></axis></joint>
  </model>
</world></sdf>""",
    )
    w = load_world(world, search_path=(models,))
    spot = mat_np((10, 0, 0), (0, 0, H))
    fw = w.model("front_wheel")
    assert_pose(fw.pose_world, spot @ mat_np((1, 0, 0), (0, 0, 0)))
    assert_pose(fw.link("hub").pose_world, spot @ mat_np((1, 0, 0.1), (0, 0, 0)))
    mesh = fw.link("hub").visuals[0].geometry
    assert isinstance(mesh, Mesh) and mesh.path == str((models / "wheel" / "meshes" / "hub.stl").resolve())
    assert mesh.scale == (2, 2, 2)
    crate = w.model("crate")
    assert crate.static and crate.source.endswith("crate.sdf")
    assert_pose(crate.link("body").pose_world, mat_np((0, 5, 0), (0, 0, 0)))
    car = w.model("car")
    car_world = spot @ mat_np((1, 0, 1), (0, 0, 0))
    assert_pose(car.pose_world, car_world)
    # placement_frame 'mount' (0.1 below the hub) is put at (0, 0.3, 0): the hub lands 0.1 above it
    assert_pose(car.link("w1::hub").pose_world, car_world @ mat_np((0, 0.3, 0.1), (0, 0, 0)))
    assert car.joint("axle").child == "w1::hub"
    assert {f.name for f in car.frames} == {"w1::mount", "w1"}


def test_world_physics_lights_and_plugins_are_read() -> None:
    text = """<sdf version="1.10"><world name="x">
      <physics name="a" type="ode"><max_step_size>0.01</max_step_size></physics>
      <physics name="b" type="ode" default="true"><max_step_size>0.002</max_step_size>
        <real_time_factor>0</real_time_factor></physics>
      <gravity>0 0 -1.62</gravity>
      <light name="lamp" type="point"><pose>1 2 3 0 0 0</pose></light>
      <plugin filename="gz-sim-physics-system" name="gz::sim::systems::Physics"/>
      <plugin filename="custom" name="x"><a>1</a><a>2</a><nested><b>3</b></nested></plugin>
    </world></sdf>"""
    from diffctl.description.sdf_loader import parse_world

    w = parse_world(text)
    assert (w.physics.max_step_size_s, w.physics.real_time_factor, w.physics.gravity) == (0.002, 0.0, (0, 0, -1.62))
    assert w.lights[0].type == "point" and w.lights[0].pose_world.xyz == (1, 2, 3)
    custom = w.plugins[1]
    assert custom.get_all("a") == ["1", "2"] and custom.as_dict()["a"] == "1"
    assert "<b>3</b>" in custom.xml
    assert [p.filename for _, p in w.all_plugins()] == ["gz-sim-physics-system", "custom"]


@pytest.mark.parametrize("version", ["1.6", "1.7", "1.8", "1.9", "1.10", "1.11"])
def test_every_supported_version_loads_the_same_geometry(version: str) -> None:
    text = f"""<sdf version="{version}"><model name="m"><pose>0 0 1 0 0 0</pose>
      <link name="a"><inertial><mass>1</mass><inertia><ixx>1</ixx><iyy>1</iyy><izz>1</izz></inertia></inertial>
        <collision name="c"><pose>0 0 0.5 0 0 0</pose><geometry><capsule><radius>0.1</radius><length>0.3</length>
        </capsule></geometry></collision></link>
    </model></sdf>"""
    m = parse_model(text)
    assert m.link("a").pose_world.xyz == (0, 0, 1)
    assert m.link("a").collisions[0].pose_link.xyz == (0, 0, 0.5)
