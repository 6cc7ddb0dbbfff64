"""ros_gz_sim's `create` as `diffctl spawn entity`: its flags in gflags spellings, create's precedence between
sources and ROS parameters, model files found as Gazebo finds them, and a real spawn into a running sim."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pytest
from sim_helpers import CAR
from test_sim_process import query, run_cli, start_sim

from diffctl.errors import ConfigError
from diffctl.sim.spawn_entity import build_request, gflags_args, resolve_model_file


@pytest.mark.parametrize(
    ("argv", "expected", "warned"),
    [
        (["-allow_renaming", "-name", "r"], ["--allow-renaming", "-name", "r"], False),
        (["-allow_renaming", "true"], ["--allow-renaming"], False),
        (["-allow_renaming", "false"], ["--allow-renaming"], True),  # gflags: the word is not the flag's value
        (["-allow_renaming=false", "-x=-1.5", "-Y=3"], ["--no-allow-renaming", "-x", "-1.5", "-Y", "3"], False),
        (["--allow_renaming=TRUE", "--name=a=b"], ["--allow-renaming", "--name=a=b"], False),
    ],
)
def test_gflags_spellings(argv: list[str], expected: list[str], warned: bool) -> None:
    out, notes = gflags_args(argv)
    assert out == expected
    assert bool(notes) == warned


def test_a_bool_flag_with_a_non_boolean_value_is_refused() -> None:
    r = run_cli("spawn", "entity", "-allow_renaming=perhaps", "-topic", "robot_description")
    assert r.returncode == 2 and "'perhaps' is not a boolean" in r.stderr


def test_sources_follow_creates_precedence_and_parameters_win() -> None:
    flags = {"file": "a.sdf", "string": "<sdf/>", "topic": "t", "param": None, "name": "flag_name", "x": 1.0}
    req = build_request(flags, {})
    assert (req.source, req.value, req.name) == ("file", "a.sdf", "flag_name")
    assert req.pose == {"x": 1.0, "y": 0.0, "z": 0.0, "roll": 0.0, "pitch": 0.0, "yaw": 0.0}
    req = build_request({**flags, "file": None}, {})
    assert (req.source, req.value) == ("string", "<sdf/>")
    req = build_request({**flags, "file": None, "param": "desc"}, {"desc": "<robot name='p'/>"})
    assert (req.source, req.value) == ("string", "<robot name='p'/>")
    # parameters: file > string > topic, and ahead of every flag; a non-zero pose parameter wins
    req = build_request(
        flags,
        {
            "topic": "/other",
            "string": "<sdf version='1.8'/>",
            "name": "param_name",
            "x": 0,
            "Y": 2,
            "allow_renaming": True,
        },
    )
    assert (req.source, req.value, req.name, req.allow_renaming) == (
        "string",
        "<sdf version='1.8'/>",
        "param_name",
        True,
    )
    assert (req.pose["x"], req.pose["yaw"]) == (1.0, 2.0)
    assert build_request({"topic": "robot_description"}, {}).pose is None


@pytest.mark.parametrize(
    ("flags", "params", "message"),
    [
        ({}, {}, "no model given"),
        ({"param": "missing"}, {}, "-param missing: this node has no parameter 'missing'"),
        ({"topic": "t", "z": math.inf}, {}, "-z inf must be a finite number"),
        ({"topic": "t"}, {"name": 3}, "parameter 'name' of create must be a str"),
    ],
)
def test_bad_requests_are_config_errors(flags: dict[str, Any], params: dict[str, Any], message: str) -> None:
    with pytest.raises(ConfigError) as e:
        build_request(flags, params)
    assert message in str(e.value)


def test_model_files_are_found_as_gazebo_finds_them(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    models = tmp_path / "models"
    (models / "box").mkdir(parents=True)
    (models / "box" / "model.sdf").write_text("<sdf/>")
    (models / "box" / "model.config").write_text("<model><sdf version='1.8'>model.sdf</sdf></model>")
    monkeypatch.setenv("GZ_SIM_RESOURCE_PATH", str(models))
    assert resolve_model_file("model://box", tmp_path) == models / "box" / "model.sdf"
    assert resolve_model_file(str(models / "box"), tmp_path) == models / "box" / "model.sdf"
    assert resolve_model_file("box/model.sdf", tmp_path) == models / "box" / "model.sdf"
    with pytest.raises(ConfigError, match="-file model://nope: no such model file"):
        resolve_model_file("model://nope", tmp_path)


def test_a_missing_file_exits_2_before_waiting_for_a_simulator(tmp_path: Path) -> None:
    r = run_cli("spawn", "entity", "-file", str(tmp_path / "nope.sdf"), "-name", "x", "--timeout", "600")
    assert r.returncode == 2
    assert r.stderr.strip().splitlines() == [
        f"error: -file {tmp_path / 'nope.sdf'}: no such model file "
        "(give a path, a model folder, or a model:// URI found on "
        "GZ_SIM_RESOURCE_PATH)"
    ]


@pytest.mark.slow
def test_create_spawns_from_a_namespaced_topic_renames_and_places(router: str, procs: Any, tmp_path: Path) -> None:
    from tests.probe import Probe

    sim, session = start_sim(procs, "-v", "3")  # paused: poses stay where they were put
    node = Probe("description_source", namespace="/r1")
    try:
        pub = node.create_publisher("robot_description", "std_msgs/msg/String", latched=True)
        pub.publish({"data": CAR.read_text()})
        # as a launch file passes them: relative topic, the node in namespace /r1, negative values, gflags bools
        args = [
            "-topic",
            "robot_description",
            "-name",
            "car",
            "-allow_renaming",
            "true",
            "-x",
            "-1.5",
            "-y=2",
            "-z",
            "0.25",
            "-R",
            "0",
            "-P",
            "0",
            "-Y",
            "-0.5",
        ]
        r = run_cli("spawn", "entity", *args, "--ros-args", "-r", "__ns:=/r1")
        assert r.returncode == 0, r.stderr
        r = run_cli("spawn", "entity", *args, "--ros-args", "-r", "__ns:=/r1")
        assert r.returncode == 0 and "spawned 'car_1'" in r.stdout, r.stdout + r.stderr
        r = run_cli("spawn", "entity", "-file", str(CAR), "-name", "car", "-allow_renaming=false")
        assert r.returncode == 1 and "already exists" in r.stderr
        models = {m["name"]: m["pose"] for m in query(session, "gz/world/empty/state")["models"]}
        assert set(models) == {"ground_plane", "car", "car_1"}
        pose = models["car"]
        assert (pose["x"], pose["y"], pose["z"], pose["yaw"]) == pytest.approx((-1.5, 2.0, 0.25, -0.5), abs=1e-6)
    finally:
        node.close()
    assert sim.poll() is None
    assert procs.stop(sim) == 0


def test_gz_spawn_model_launch_passes_creates_parameters(tmp_path: Path) -> None:
    from tests.launch_requests import started

    path = tmp_path / "spawn.launch.py"
    path.write_text(
        "import os\n"
        "from ament_index_python.packages import get_package_share_directory\n"
        "from launch import LaunchDescription\n"
        "from launch.actions import IncludeLaunchDescription\n"
        "from launch.launch_description_sources import PythonLaunchDescriptionSource\n"
        "def generate_launch_description():\n"
        "    f = os.path.join(get_package_share_directory('ros_gz_sim'), 'launch', 'gz_spawn_model.launch.py')\n"
        "    args = {'topic': 'robot_description', 'entity_name': 'bot', 'z': '0.3', 'Y': '-1',\n"
        "            'allow_renaming': 'true'}\n"
        "    return LaunchDescription([IncludeLaunchDescription(PythonLaunchDescriptionSource(f),\n"
        "                              launch_arguments=args.items())])\n"
    )
    (create,) = started(path).started
    assert create.argv[-2:] == ["spawn", "entity"]
    req = build_request({}, create.params())
    assert (req.source, req.value, req.name, req.allow_renaming) == ("topic", "robot_description", "bot", True)
    assert req.pose == {"x": 0.0, "y": 0.0, "z": 0.3, "roll": 0.0, "pitch": 0.0, "yaw": -1.0}
    # as text, the way some launch files hand them over
    req = build_request({"topic": "t"}, {"allow_renaming": "False", "x": "1.5", "world": ""})
    assert (req.allow_renaming, req.pose["x"], req.world) == (False, 1.5, None)
