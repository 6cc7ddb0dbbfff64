"""A user's interface package in a workspace (package.xml + CMakeLists with rosidl_generate_interfaces, a
message, a service and an action using geometry_msgs and std_msgs): importable, hashed exactly as rosidl's own
generator hashes it (rosidl_adapter + rosidl_generator_type_description from the Jazzy wheels, run in the
oracle venv), and usable on the bus."""

from __future__ import annotations

import json
import shutil
import time
from pathlib import Path

import pytest

from tests.interfaces.programs import run_ours
from tests.oracle import jazzy_venv

FILES = {
    "msg/Obstacle.msg": """# an obstacle seen by the robot
std_msgs/Header header
geometry_msgs/Point position
float64 radius 0.5
string<=16 label "cone"
uint8 KIND_STATIC=0
uint8 KIND_DYNAMIC=1
uint8 kind
""",
    "msg/ObstacleArray.msg": "Obstacle[] obstacles\nint32[<=4] ids\nbool[2] flags\n",
    "srv/SetSpeed.srv": "float64 speed  # m/s\n---\nbool ok\nstring message\n",
    "action/Drive.action": "geometry_msgs/Pose target\n---\nfloat64 distance\n---\nfloat32 progress\n",
}
CMAKELISTS = """cmake_minimum_required(VERSION 3.8)
project(robot_interfaces)
find_package(rosidl_default_generators REQUIRED)
find_package(geometry_msgs REQUIRED)
set(msg_files "msg/Obstacle.msg" "msg/ObstacleArray.msg")
rosidl_generate_interfaces(${PROJECT_NAME}
  ${msg_files}
  "srv/SetSpeed.srv"
  "action/Drive.action"
  DEPENDENCIES std_msgs geometry_msgs
)
ament_package()
"""
PACKAGE_XML = """<?xml version="1.0"?>
<package format="3">
  <name>robot_interfaces</name><version>0.1.0</version><description>d</description>
  <maintainer email="a@b.c">a</maintainer><license>MIT</license>
  <buildtool_depend>rosidl_default_generators</buildtool_depend>
  <depend>geometry_msgs</depend><depend>std_msgs</depend>
  <member_of_group>rosidl_interface_packages</member_of_group>
  <export><build_type>ament_cmake</build_type></export>
</package>
"""

# rosidl's own pipeline, as colcon runs it: .msg/.srv/.action → .idl → type description JSON with hashes.
ROSIDL = r'''
import json, pathlib, sys, tempfile
from rosidl_adapter.msg import convert_msg_to_idl
from rosidl_adapter.srv import convert_srv_to_idl
from rosidl_adapter.action import convert_action_to_idl
from rosidl_generator_type_description import generate_type_hash
src, pkg, share = pathlib.Path(SRC), PKG, pathlib.Path(SHARE)
out = pathlib.Path(tempfile.mkdtemp())
tuples = []
for kind, convert in (("msg", convert_msg_to_idl), ("srv", convert_srv_to_idl), ("action", convert_action_to_idl)):
    for f in sorted((src / kind).glob("*." + kind)):
        convert(src, pkg, pathlib.Path(kind) / f.name, out / "idl" / kind)
        tuples.append(f"{out / 'idl'}:{kind}/{f.stem}.idl")
args = {"package_name": pkg, "output_dir": str(out / "json"), "idl_tuples": tuples,
        "include_paths": [f"{d.name}:{d}" for d in share.iterdir() if (d / "msg").is_dir()]}
(out / "args.json").write_text(json.dumps(args))
hashes = {}
for generated in generate_type_hash(str(out / "args.json")):
    for h in json.loads(pathlib.Path(generated).read_text())["type_hashes"]:
        hashes[h["type_name"]] = h["hash_string"]
print(json.dumps(hashes))
'''


def rosidl_hashes(src: Path, pkg: str) -> dict[str, str]:
    code = f"SRC, PKG, SHARE = {str(src)!r}, {pkg!r}, {str(jazzy_venv.VENV / 'share')!r}\n" + ROSIDL
    return json.loads(jazzy_venv.run_python(code).stdout.strip().splitlines()[-1])


@pytest.fixture
def workspace(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    pkg = tmp_path / "ws" / "src" / "robot_interfaces"
    for rel, text in FILES.items():
        (pkg / rel).parent.mkdir(parents=True, exist_ok=True)
        (pkg / rel).write_text(text)
    (pkg / "CMakeLists.txt").write_text(CMAKELISTS)
    (pkg / "package.xml").write_text(PACKAGE_XML)
    monkeypatch.setenv("DIFFCTL_WORKSPACE", str(tmp_path / "ws"))
    return tmp_path / "ws"


def test_user_package_imports_and_hashes_as_rosidl(workspace: Path) -> None:
    real = rosidl_hashes(workspace / "src" / "robot_interfaces", "robot_interfaces")
    assert "robot_interfaces/action/Drive_SendGoal" in real and len(real) > 20
    ours = run_ours(f"NAMES = {sorted(real)!r}\n" + r'''
from robot_interfaces.msg import Obstacle, ObstacleArray
from robot_interfaces.srv import SetSpeed
from robot_interfaces.action import Drive
from diffctl.interfaces import types
for n in NAMES:
    obs(n, lambda n=n: types.type_hash(n))
obs('obstacle', lambda: Obstacle())
obs('constants', lambda: (Obstacle.KIND_DYNAMIC, Obstacle.RADIUS__DEFAULT, Obstacle.LABEL__DEFAULT))
obs('label bound', lambda: Obstacle.get_fields_and_field_types())
obs('array', lambda: ObstacleArray(ids=[1, 2]))
obs('srv', lambda: (SetSpeed.Request(speed=1.0), SetSpeed.Response()))
obs('action', lambda: (Drive.Goal(), Drive.Impl.FeedbackMessage(), Drive.Impl.GetResultService.Response()))
''', {"DIFFCTL_WORKSPACE": str(workspace)})
    assert {n: ours[n][1] for n in real} == real
    assert ours["obstacle"][1] == (
        "robot_interfaces.msg.Obstacle(header=std_msgs.msg.Header(stamp=builtin_interfaces.msg.Time(sec=0, "
        "nanosec=0), frame_id=''), position=geometry_msgs.msg.Point(x=0.0, y=0.0, z=0.0), radius=0.5, "
        "label='cone', kind=0)")
    assert ours["constants"][1] == "(1, 0.5, 'cone')"
    assert "'label': 'string<16>'" in ours["label bound"][1]
    assert ours["array"][1] == "robot_interfaces.msg.ObstacleArray(obstacles=[], ids=[1, 2], flags=[False, False])"


def test_shipped_interfaces_hash_as_rosidl(tmp_path: Path) -> None:
    """The interface texts diffctl ships that no Jazzy wheel here has (example_interfaces; tf2_msgs' service and
    action, whose messages come from the graph tests' upstream texts) hashed by rosidl itself."""
    from diffctl.interfaces import registry, types

    src = Path(registry.JAZZY) / "example_interfaces"
    real = rosidl_hashes(src, "example_interfaces")
    assert "example_interfaces/action/Fibonacci_SendGoal" in real
    tf2 = tmp_path / "tf2_msgs"
    shutil.copytree(Path(registry.JAZZY) / "tf2_msgs", tf2)
    shutil.copytree(Path(__file__).parents[1] / "graph" / "upstream_interfaces" / "tf2_msgs" / "msg", tf2 / "msg")
    tf2_real = rosidl_hashes(tf2, "tf2_msgs")
    assert "tf2_msgs/action/LookupTransform_FeedbackMessage" in tf2_real and "tf2_msgs/srv/FrameGraph" in tf2_real
    real |= tf2_real
    registry.package("example_interfaces")
    registry.package("tf2_msgs")
    assert {n: types.type_hash(n) for n in real} == real


def test_user_package_on_the_bus(workspace: Path, router: str) -> None:
    from diffctl.bus import wire
    from diffctl.interfaces import deserialize, get_interface, registry, serialize, type_hash, type_name, types
    from diffctl.interfaces import workspace as ws_index
    from tests.probe import Probe

    registry.reset()
    ws_index.reset()
    array_cls = get_interface("robot_interfaces/msg/ObstacleArray")
    obstacle = get_interface("robot_interfaces/msg/Obstacle")
    point = get_interface("geometry_msgs/msg/Point")
    msg = array_cls(obstacles=[obstacle(kind=1, position=point(x=2.0))], ids=[7], flags=[True, False])
    a, b = Probe("talker"), Probe("listener")
    try:
        raw: list[bytes] = []
        decoded: list = []
        b.create_subscription("/obstacles", type_name(array_cls), raw.append, raw=True)
        b.create_subscription("/obstacles", type_name(array_cls), decoded.append)
        pub = a.create_publisher("/obstacles", type_name(array_cls))
        assert type_hash(array_cls) in wire.topic_key(0, "/obstacles", type_name(array_cls))
        deadline = time.monotonic() + 10
        while pub.subscription_count < 2 and time.monotonic() < deadline:
            time.sleep(0.02)
        pub.publish_raw(serialize(msg))
        while not (raw and decoded) and time.monotonic() < deadline:
            time.sleep(0.02)
        assert deserialize(raw[0], array_cls) == msg
        # the bus's own typestore knows the workspace type too: its subscribers decode it as any other
        assert decoded[0].obstacles[0].position.x == 2.0 and list(decoded[0].ids) == [7]
        assert types.type_hash("robot_interfaces/msg/ObstacleArray") == type_hash(msg)
    finally:
        a.close()
        b.close()


def test_user_package_in_diffctls_tools(workspace: Path) -> None:
    """`diffctl interface show` (and every bus tool) knows the workspace's types without an import first."""
    import os
    import subprocess
    import sys

    env = {**os.environ, "DIFFCTL_WORKSPACE": str(workspace)}
    p = subprocess.run([sys.executable, "-m", "diffctl", "interface", "show", "robot_interfaces/srv/SetSpeed"],
                       env=env, capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stderr
    assert p.stdout.split() == ["float64", "speed", "---", "bool", "ok", "string", "message"]
    p = subprocess.run([sys.executable, "-m", "diffctl", "interface", "show", "robot_interfaces/msg/Obstacle"],
                       env=env, capture_output=True, text=True, timeout=60)
    assert "uint8 KIND_DYNAMIC=1" in p.stdout and "geometry_msgs/msg/Point position" in p.stdout, p.stdout + p.stderr
