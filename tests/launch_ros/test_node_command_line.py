"""Node's command line, as launch_ros builds it: name, namespace (pushed and own), the scope's parameters and
remappings before the node's own, parameter dictionaries written to a file for the node, scoped groups
dropping what was set inside them; and the executable of a package through diffctl's package index."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

from diffctl.launch.actions import GroupAction
from diffctl.launch.logging import launch_config
from diffctl.launch.substitutions import TextSubstitution
from diffctl.launch_ros.actions import Node, PushRosNamespace, SetParameter, SetParametersFromFile, SetRemap
from diffctl.launch_ros.descriptions import Parameter

from .conftest import DATA, Records, run

ECHO = str(DATA / "echo_args.py")


def echo_node(out: Path, **kw) -> Node:
    return Node(executable=sys.executable, arguments=[ECHO], additional_env={"ECHO_TO": str(out)}, **kw)


def test_scope_settings_come_first_and_stay_in_their_group(tmp_path: Path) -> None:
    scope_file = tmp_path / "scope.yaml"
    scope_file.write_text("/**:\n  ros__parameters:\n    from_scope: 1\n")
    own_file = tmp_path / "own.yaml"
    own_file.write_text("/robot/ns/talker:\n  ros__parameters:\n    from_file: 2\n")
    inside, outside = tmp_path / "inside.json", tmp_path / "outside.json"
    talker = echo_node(
        inside,
        name="talker",
        namespace="ns",
        ros_arguments=["--log-level", "debug"],
        parameters=[
            {"rate_hz": 10, "frame": "base", "wheels": {"radius_m": 0.04, "names": ["l", "r"]}},
            str(own_file),
            Parameter("gain", TextSubstitution(text="3"), value_type=int),
        ],
        remappings=[("chatter", "/chat")],
    )
    code, context = run([
        GroupAction(
            [
                PushRosNamespace("robot"),
                SetParameter("use_sim_time", True),
                SetParametersFromFile(str(scope_file)),
                SetRemap("/tf", "tf"),
                talker,
            ],
            scoped=True,
        ),
        echo_node(outside),
    ])
    assert code == 0
    seen = json.loads(inside.read_text())
    argv = seen["argv"]
    dict_file = argv[argv.index(str(own_file)) - 2]
    assert argv == [
        "--ros-args", "--log-level", "debug",
        "--ros-args", "-r", "__node:=talker", "-r", "__ns:=/robot/ns",
        "-p", "use_sim_time:=True", "--params-file", str(scope_file),
        "--params-file", dict_file, "--params-file", str(own_file), "-p", "gain:=3\n...\n",
        "-r", "/tf:=tf", "-r", "chatter:=/chat",
    ]  # fmt: skip
    assert seen["params_files"][dict_file] == {
        "/robot/ns/talker": {
            "ros__parameters": {"rate_hz": 10, "frame": "base", "wheels.radius_m": 0.04, "wheels.names": ["l", "r"]}
        }
    }
    assert Path(dict_file).parent == Path(launch_config.log_dir)  # kept with the run's logs, not in /tmp
    assert talker.node_name == "/robot/ns/talker"
    assert json.loads(outside.read_text())["argv"] == ["--ros-args"]  # nothing of the group leaked out
    assert not hasattr(context.locals, "ros_adapter")  # plain nodes: the launch made no ROS node of its own


def test_a_node_without_a_full_name_gets_its_dictionary_for_every_node(tmp_path: Path) -> None:
    out = tmp_path / "out.json"
    code, _ = run([echo_node(out, parameters=[{"x": "1"}])])
    assert code == 0
    seen = json.loads(out.read_text())
    assert list(seen["params_files"].values()) == [{"/**": {"ros__parameters": {"x": "1"}}}]


def test_a_package_executable_starts_diffctl_s_component_named_after_the_executable() -> None:
    from diffctl.launch.actions import RegisterEventHandler, Shutdown
    from diffctl.launch.event_handlers import OnProcessStart

    talker = Node(package="demo_nodes_py", executable="talker", name="speaker", output="log")
    started: list[dict] = []
    code, _ = run([
        RegisterEventHandler(OnProcessStart(
            target_action=talker,
            on_start=lambda event, context: started.append(dict(event.action.process_details)) or [Shutdown()],
        )),
        talker,
    ])  # fmt: skip
    assert code == 0
    details = started[0]
    assert details["cmd"][:3] == [sys.executable, "-m", "diffctl.demo_nodes"]
    assert details["cmd"][3:] == ["demo_nodes_py", "talker", "--ros-args", "-r", "__node:=speaker"]
    assert details["name"].startswith("talker-")  # launch numbers processes: talker-1, talker-2, …


@pytest.mark.parametrize(
    ("node", "message"),
    [
        (dict(package="no_such_package", executable="x"), "unknown package 'no_such_package'"),
        (dict(package="demo_nodes_py", executable="no_such_exe"), "has no executable 'no_such_exe'"),
        (dict(executable="true", name="bad-name"), "node name must not contain characters other than"),
        (dict(executable="true", namespace="1ns"), "namespace must not have a token that starts with a number"),
    ],
)
def test_what_cannot_start_fails_the_launch_naming_it(node: dict, message: str) -> None:
    with Records("launch") as records:
        code, _ = run([Node(**node)])
    assert code == 1
    assert any(message in m for m in records.messages), records.messages
