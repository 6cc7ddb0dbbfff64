"""SDF features community packages use: `<include merge="true">`, COLLADA meshes, XML as lenient as TinyXML2."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import pytest

from diffctl.description.sdf_loader import load_model, load_world
from diffctl.errors import DescriptionError

DATA = Path(__file__).resolve().parent / "data"

KIT = """<?xml version="1.0"?>
<sdf version="1.9">
  <model name="sensor_kit">
    <pose>0 0 0.5 0 0 0</pose>
    <static>true</static>
    <link name="kit_link">
      <pose>0.1 0 0 0 0 0</pose>
      <inertial><mass>0.1</mass><inertia><ixx>1e-4</ixx><iyy>1e-4</iyy><izz>1e-4</izz></inertia></inertial>
    </link>
    <link name="lidar_link">
      <pose relative_to="kit_link">0 0 0.05 0 0 0</pose>
      <inertial><mass>0.1</mass><inertia><ixx>1e-4</ixx><iyy>1e-4</iyy><izz>1e-4</izz></inertia></inertial>
    </link>
    <joint name="lidar_joint" type="fixed"><parent>kit_link</parent><child>lidar_link</child></joint>
    <frame name="mount"><pose>0 0 -0.01 0 0 0</pose></frame>
    <plugin filename="gz-sim-pose-publisher-system" name="gz::sim::systems::PosePublisher"/>
  </model>
</sdf>
"""

ROBOT = """<?xml version="1.0"?>
<sdf version="1.9">
  <model name="robot">
    <link name="base">
      <inertial><mass>1</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
    </link>
    <include merge="true">
      <uri>model://sensor_kit</uri>
      <pose relative_to="base">1 0 0.2 0 0 {yaw}</pose>
      <plugin filename="gz-sim-odometry-publisher-system" name="gz::sim::systems::OdometryPublisher"/>
    </include>
    <joint name="kit_mount" type="fixed"><parent>base</parent><child>kit_link</child></joint>
  </model>
</sdf>
"""


def _models(tmp_path: Path, yaw: float = 0.0) -> Path:
    kit = tmp_path / "models" / "sensor_kit"
    kit.mkdir(parents=True)
    (kit / "model.sdf").write_text(KIT)
    robot = tmp_path / "robot.sdf"
    robot.write_text(ROBOT.format(yaw=yaw))
    return robot


def test_merge_include_puts_the_models_parts_in_the_parent_unscoped(tmp_path: Path) -> None:
    robot = load_model(_models(tmp_path, yaw=math.pi / 2), search_path=(tmp_path / "models",))
    assert [link.name for link in robot.links] == ["base", "kit_link", "lidar_link"]
    assert [j.name for j in robot.joints] == ["lidar_joint", "kit_mount"]
    # the include's pose places the merged model frame (proxy), the links keep their poses inside it
    kit = robot.link("kit_link").pose_model
    assert kit.xyz == pytest.approx((1.0, 0.1, 0.2))
    assert robot.link("lidar_link").pose_model.xyz == pytest.approx((1.0, 0.1, 0.25))
    frames = {f.name: f for f in robot.frames}
    assert frames["_merged__sensor_kit__model__"].pose_model.xyz == pytest.approx((1.0, 0.0, 0.2))
    assert frames["mount"].pose_model.xyz == pytest.approx((1.0, 0.0, 0.19))  # attached to the proxy frame
    assert frames["mount"].attached_to == "kit_link"
    # the included model's plugins and the include's own both end up on the parent
    assert [p.filename for p in robot.plugins] == ["gz-sim-pose-publisher-system", "gz-sim-odometry-publisher-system"]
    assert robot.static is False  # <static> of a merged model is dropped


def test_merge_include_name_clash_and_non_model_are_errors(tmp_path: Path) -> None:
    path = _models(tmp_path)
    path.write_text(path.read_text().replace('<link name="base">', '<link name="kit_link">').replace(">base<", ">x<"))
    with pytest.raises(DescriptionError, match="'kit_link' is used twice"):
        load_model(path, search_path=(tmp_path / "models",))
    light = tmp_path / "models" / "lamp"
    light.mkdir()
    (light / "model.sdf").write_text('<sdf version="1.9"><light name="l" type="point"/></sdf>')
    path.write_text(ROBOT.format(yaw=0).replace("model://sensor_kit", "model://lamp"))
    with pytest.raises(DescriptionError, match=r'merge="true"> needs a <model>'):
        load_model(path, search_path=(tmp_path / "models",))


def test_merge_include_into_a_world_adds_its_nested_models(tmp_path: Path) -> None:
    scene = tmp_path / "scene"
    scene.mkdir()
    (scene / "model.sdf").write_text(
        '<sdf version="1.9"><model name="scene">'
        '<model name="wall"><static>true</static><pose>2 0 0 0 0 0</pose><link name="l"/></model>'
        '<model name="post"><static>true</static><pose>0 3 0 0 0 0</pose><link name="l"/></model>'
        "</model></sdf>"
    )
    world = tmp_path / "w.sdf"
    world.write_text(
        '<sdf version="1.9"><world name="w"><include merge="true"><uri>scene</uri>'
        "<pose>10 0 0 0 0 0</pose></include></world></sdf>"
    )
    models = {m.name: m for m in load_world(world).models}
    assert sorted(models) == ["post", "wall"]
    assert models["wall"].pose_world.xyz == pytest.approx((12.0, 0.0, 0.0))
    assert models["post"].pose_world.xyz == pytest.approx((10.0, 3.0, 0.0))


def test_collada_meshes_in_sdf_take_the_urdf_mesh_path(tmp_path: Path, monkeypatch) -> None:
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    folder = tmp_path / "wedge" / "meshes"
    folder.mkdir(parents=True)
    shutil.copy(DATA / "wedge.dae", folder / "wedge.dae")
    model = tmp_path / "wedge" / "model.sdf"
    model.write_text(
        '<sdf version="1.9"><model name="wedge"><static>true</static><link name="l">'
        "<collision name='c'><geometry><mesh><uri>model://wedge/meshes/wedge.dae</uri>"
        "<scale>2 2 2</scale></mesh></geometry></collision></link></model></sdf>"
    )
    geometry = load_model(model, search_path=(tmp_path,)).links[0].collisions[0].geometry
    assert geometry.path.endswith(".obj") and Path(geometry.path).is_file()
    assert geometry.uri == "model://wedge/meshes/wedge.dae" and geometry.scale == (2.0, 2.0, 2.0)
    import trimesh

    # COLLADA's <unit meter="0.01"> applied, as Gazebo's loader does
    assert trimesh.load(geometry.path, force="mesh").bounds.ravel().tolist() == pytest.approx([0, 0, 0, 0.2, 0.1, 0.05])


LENIENT = """
   <?xml version="1.0"?>
<sdf version="1.9">
  <!-- gz-sim's empty.sdf says: gz service -s /world/empty/create --reqtype gz.msgs.EntityFactory -->
  <world name="lenient &amp; fine &nbsp;">
    <gz:system_config>x</gz:system_config>
    <model name="m"><static>true</static>
      <link name="l"><pose>1 2</pose></link>
    </model>
  </world>
</sdf>
"""


def test_xml_that_sdformat_accepts_is_accepted_with_line_numbers_kept(tmp_path: Path) -> None:
    path = tmp_path / "w.sdf"
    path.write_text(LENIENT)
    with pytest.raises(DescriptionError) as e:  # the file parses; the error is the bad pose, at its own line
        load_world(path)
    assert e.value.line == 8 and "pose" in str(e.value)
    path.write_text(LENIENT.replace("<pose>1 2</pose>", "<pose>1 2 3 0 0 0</pose>"))
    world = load_world(path)
    assert world.name == "lenient & fine &nbsp;"  # TinyXML2 keeps an unknown entity as written
    assert world.models[0].links[0].pose_world.xyz == (1.0, 2.0, 3.0)


def test_xml_that_sdformat_rejects_stays_an_error_at_its_line(tmp_path: Path) -> None:
    path = tmp_path / "w.sdf"
    path.write_text('<sdf version="1.9">\n<!-- -- -->\n<world name="w">\n</wrld>\n</sdf>\n')
    with pytest.raises(DescriptionError, match="malformed XML") as e:
        load_world(path)
    assert e.value.line == 4


def test_gazebos_shapes_world_by_name_settles_on_its_ground(tmp_path: Path, monkeypatch) -> None:
    """`gz sim shapes.sdf` finds diffctl's copy; every shape, the ellipsoid (a mesh here) too, rests where
    Gazebo's would: its lowest point on the ground plane after a second of real PyBullet physics."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    monkeypatch.delenv("GZ_SIM_RESOURCE_PATH", raising=False)
    from diffctl.sim.cli import find_world
    from diffctl.sim.world import PhysicsWorld

    world = load_world(find_world("shapes.sdf"))
    assert world.name == "shapes"
    pw = PhysicsWorld(world.physics)
    bodies = {m.name: pw.add_model(m) for m in world.models}
    for _ in range(1000):
        pw.step()
    rest_z = {"box": 0.5, "cylinder": 0.5, "sphere": 0.5, "capsule": 0.5, "ellipsoid": 0.5}
    for name, z in rest_z.items():
        pose = bodies[name].pose()
        assert pose.xyz[2] == pytest.approx(z, abs=0.02), name
    assert bodies["ellipsoid"].pose().xyz[1] == pytest.approx(3.0, abs=0.01)


DEMO_WORLDS = {  # the world each ros_gz_sim_demos launch file names → what its bridge arguments expect
    "diff_drive.sdf": {"vehicle_blue", "vehicle_green"},
    "linear_battery_demo.sdf": {"vehicle_blue"},
    "sensors.sdf": {"/imu", "/magnetometer", "/air_pressure"},
    "gpu_lidar_sensor.sdf": {"/lidar"},
    "camera_sensor.sdf": {"/camera"},
    "triggered_camera_sensor.sdf": {"/camera"},
    "sensors_demo.sdf": {"/camera", "/depth_camera", "/rgbd_camera", "/lidar"},
    "spherical_coordinates.sdf": {"/navsat"},
}


@pytest.mark.parametrize("name", sorted(DEMO_WORLDS))
def test_gazebos_example_worlds_the_ros_gz_demos_name_are_known(name: str, monkeypatch) -> None:
    monkeypatch.delenv("GZ_SIM_RESOURCE_PATH", raising=False)
    from lxml import etree

    from diffctl.sim.cli import find_world

    path = find_world(name)
    world = load_world(path, check_files=False)
    models = {m.name for m in world.models}
    # every sensor's topic as written (sensors diffctl does not simulate yet are listed in Model.ignored)
    topics = {"/" + t.text.strip().strip("/") for t in etree.parse(str(path)).iter("topic") if t.text}
    wanted = DEMO_WORLDS[name]
    assert wanted <= models | topics, (wanted, models, topics)
    assert "ground_plane" in models and world.lights
