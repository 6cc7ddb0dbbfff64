"""`gz` as users and launch files call it, against diffctl's simulator on a real router (gz-transport13 /
gz-sim8 output shapes), and the text format its payloads travel in."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

from diffctl.gz.textproto import format_message, parse_message
from tests.waiting import wait_for

# the venv's console script (pyproject's [project.scripts] gz); the same entry point without it
GZ_SCRIPT = shutil.which("gz", path=str(Path(sys.executable).parent))
GZ = [GZ_SCRIPT] if GZ_SCRIPT else [sys.executable, "-c", "from diffctl.gz.cli import main; main()"]

BOX_WORLD = """<?xml version="1.0"?>
<sdf version="1.9">
  <world name="shapes">
    <include><uri>https://fuel.gazebosim.org/1.0/OpenRobotics/models/Ground Plane</uri></include>
    <include><uri>https://fuel.gazebosim.org/1.0/OpenRobotics/models/Sun</uri></include>
    <model name="box">
      <pose>1 2 0.5 0 0 0</pose>
      <link name="link">
        <inertial><mass>1</mass><inertia><ixx>0.16</ixx><iyy>0.16</iyy><izz>0.16</izz></inertia></inertial>
        <collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision>
      </link>
    </model>
    <model name="pendulum">
      <pose>0 -2 0 0 0 0</pose>
      <link name="base">
        <inertial><mass>5</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia></inertial>
        <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>
      </link>
      <link name="arm">
        <pose>0 0 1 0 0 0</pose>
        <inertial><mass>0.5</mass><pose>0 0 0.25 0 0 0</pose>
          <inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.001</izz></inertia></inertial>
        <sensor name="tip_imu" type="imu"><pose>0 0 0.5 0 0 0</pose><update_rate>10</update_rate></sensor>
      </link>
      <joint name="anchor" type="fixed"><parent>world</parent><child>base</child></joint>
      <joint name="hinge" type="revolute">
        <parent>base</parent><child>arm</child><pose>0 0 -0.5 0 0 0</pose>
        <axis><xyz>0 1 0</xyz></axis>
      </joint>
    </model>
  </world>
</sdf>
"""


def test_text_format_prints_as_protobuf_and_reads_what_users_type() -> None:
    msg = {
        "header": {"stamp": {"sec": 3, "nsec": 0}, "data": []},
        "linear": {"x": 0.5, "y": 0.0, "z": 0.0},
        "angular": {"x": 0.0, "y": 0.0, "z": -1.25},
        "name": 'a "b"\n',
        "pixel_format_type": "RGB_INT8",
        "ranges": [1.0, float("inf")],
    }
    assert format_message(msg) == (
        "header {\n  stamp {\n    sec: 3\n  }\n}\nlinear {\n  x: 0.5\n}\nangular {\n  z: -1.25\n}\n"
        'name: "a \\"b\\"\\n"\npixel_format_type: RGB_INT8\nranges: 1\nranges: inf\n'
    )
    assert parse_message("linear: {x: 0.5}, angular {z: -1.25e0}  # turn") == {
        "linear": {"x": 0.5},
        "angular": {"z": -1.25},
    }
    assert parse_message('data: "hi \\"there\\"" flag: true n: 3 v: [1, 2] v2 < a: 1 >') == {
        "data": 'hi "there"',
        "flag": True,
        "n": 3,
        "v": [1, 2],
        "v2": {"a": 1},
    }
    assert parse_message("pose {position {x: 1}} pose {position {x: 2}}") == {
        "pose": [{"position": {"x": 1}}, {"position": {"x": 2}}]
    }
    from diffctl.gz.textproto import json_value

    assert json_value({**msg, "data": b"\x00\x01", "big": 2**60}) == {
        "header": {"stamp": {"sec": 3}},
        "linear": {"x": 0.5},
        "angular": {"z": -1.25},
        "name": 'a "b"\n',
        "pixelFormatType": "RGB_INT8",
        "ranges": [1.0, "Infinity"],
        "data": "AAE=",
        "big": str(2**60),
    }
    from diffctl.errors import MessageError

    with pytest.raises(MessageError, match="missing '}'"):
        parse_message("linear: {x: 1")


def gz(*args: str, timeout: float = 30) -> subprocess.CompletedProcess:
    return subprocess.run([*GZ, *args], capture_output=True, text=True, timeout=timeout, env=os.environ.copy())


@pytest.mark.slow
def test_gz_topic_service_model_against_a_running_world(router: str, procs, tmp_path: Path, monkeypatch) -> None:
    monkeypatch.setenv("GZ_SIM_RESOURCE_PATH", str(tmp_path))
    monkeypatch.setenv("GZ_FUEL_CACHE_PATH", str(tmp_path))
    monkeypatch.setenv("DIFFCTL_FUEL_OFFLINE", "1")
    (tmp_path / "shapes.sdf").write_text(BOX_WORLD)
    # a bare world name resolves through GZ_SIM_RESOURCE_PATH, as `gz sim shapes.sdf` does
    sim = procs.start([*GZ, "sim", "-s", "-v", "3", "shapes.sdf"], cwd=tmp_path)
    assert wait_for(lambda: "shapes" in gz("service", "-l").stdout or sim.poll() is not None, 30)
    assert sim.poll() is None, sim.stdout.read()
    services = gz("service", "-l").stdout.split()
    assert {"/gazebo/worlds", "/world/shapes/control", "/world/shapes/create", "/world/shapes/state"} <= set(services)
    topics = gz("topic", "-l").stdout.split()
    assert {"/clock", "/world/shapes/stats"} <= set(topics)
    info = gz("topic", "-i", "-t", "/clock").stdout
    assert info.startswith("Publishers [Address, Message Type]:") and "gz.msgs.Clock" in info
    listing = gz("model", "--list")
    assert listing.stdout == (
        "\nRequesting state for world [shapes]...\n\nAvailable models:\n    - ground_plane\n    - box\n"
        "    - pendulum\n"
    )
    pose = gz("model", "-m", "box").stdout
    assert "  - Name: box" in pose and "    [1.000000 2.000000 0.500000]\n" in pose
    # links and joints as gz-sim 8's ModelCommandAPI prints them (entity numbers are diffctl's own)
    info = gz("model", "-m", "pendulum").stdout
    assert "\n  - Link [" in info and "    - Name: arm\n" in info and "    - Parent: pendulum [" in info
    mass = "    - Mass (kg): 0.500000\n    - Inertial Pose [ XYZ (m) ] [ RPY (rad) ]:\n"
    assert mass + "      [0.000000 0.000000 0.250000]\n" in info
    assert "    - Inertial Matrix (kg.m^2):\n      [0.010000 0.000000 0.000000]\n" in info
    assert "    - Pose [ XYZ (m) ] [ RPY (rad) ]:\n      [0.000000 0.000000 1.000000]\n" in info  # arm, model frame
    hinge = info[info.index("    - Name: hinge"):]
    assert "    - Type: revolute\n    - Parent Link: base [" in hinge and "    - Child Link: arm [" in hinge
    assert "      [0.000000 0.000000 -0.500000]\n" in hinge and "- Axis unit vector [ XYZ ]:\n      [0 1 0]\n" in hinge
    assert "    - Parent Link: world\n" in info  # the fixed anchor: no entity named world
    # a link's sensors under it, as ModelCommandAPI lists them
    tip = info[info.index("    - Sensor ["):]
    assert tip.startswith("    - Sensor [") and "      - Name: tip_imu\n      - Parent: pendulum [" in tip
    assert "      - Pose [ XYZ (m) ] [ RPY (rad) ]:\n        [0.000000 0.000000 0.500000]\n" in tip
    only_sensor = gz("model", "-m", "pendulum", "-s", "tip_imu").stdout
    assert "\n- Sensor [" in only_sensor and "- Link [" not in only_sensor and "Model: [" not in only_sensor
    only_joint = gz("model", "-m", "pendulum", "-j", "hinge").stdout
    assert "Model: [" not in only_joint and "- Joint [" in only_joint and "- Link [" not in only_joint
    assert "Name: anchor" not in only_joint
    assert "No model named <nope> was found" in gz("model", "-m", "nope").stdout
    # UserCommands' set_pose, listed with the world's services and called as gz-transport's CLI calls it
    assert "/world/shapes/set_pose" in gz("service", "-l").stdout.split()
    set_pose = ["service", "-s", "/world/shapes/set_pose", "--reqtype", "gz.msgs.Pose", "--reptype", "gz.msgs.Boolean"]
    req = 'name: "box", position: {x: 3, y: -1, z: 0.5}, orientation: {z: 0.24740395925452294, w: 0.9689124217106447}'
    assert gz(*set_pose, "--timeout", "3000", "--req", req).stdout == "data: true\n"
    moved = gz("model", "-m", "box", "-p").stdout
    assert "    [3.000000 -1.000000 0.500000]\n    [0.000000 0.000000 0.500000]\n" in moved, moved
    # false: protobuf's text format leaves a default field out, so gz prints nothing
    assert gz(*set_pose, "--timeout", "3000", "--req", 'name: "nope"').stdout == ""
    # paused (no -r): /clock holds still until the world is unpaused through the control service
    first = gz("topic", "-e", "-t", "/clock", "-n", "1").stdout
    assert first.startswith("header {") and "sim {" in first
    reply = gz(
        "service",
        "-s",
        "/world/shapes/control",
        "--reqtype",
        "gz.msgs.WorldControl",
        "--reptype",
        "gz.msgs.Boolean",
        "--timeout",
        "3000",
        "--req",
        "pause: false",
    )
    assert reply.stdout == "data: true\n", reply.stdout + reply.stderr
    time.sleep(0.5)
    later = gz("topic", "-e", "-t", "/clock", "-n", "1").stdout
    sec = [int(line.split(":")[1]) for line in later.splitlines() if line.strip().startswith("sec:")]
    assert sec and max(sec) >= 0 and later != first
    # a publication reaches the simulator's subscribers (the world's pose topic is a publisher; use remove)
    gone = gz(
        "service",
        "-s",
        "/world/shapes/remove",
        "--reqtype",
        "gz.msgs.Entity",
        "--reptype",
        "gz.msgs.Boolean",
        "--req",
        'name: "box" type: MODEL',
    )
    assert gone.stdout == "data: true\n"
    assert "box" not in gz("model", "--list").stdout
    assert gz("sim", "--no-such-flag", "x.sdf").returncode == 2


def test_gz_is_a_console_script_of_the_project() -> None:
    import tomllib

    REPO = Path(__file__).resolve().parents[2]
    scripts = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]["scripts"]
    assert scripts["gz"] == "diffctl.gz.cli:main"
