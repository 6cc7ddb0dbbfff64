"""launch_ros's tags from XML and YAML build the same nodes as the Python API: a scoped group with a pushed
namespace, SetParameter, SetParametersFromFile, SetRemap and SetROSLogDir, and a node with nested and typed
`param`s, a parameter file, `remap`, `env`, `args` and `ros_args` — compared by what the started node received."""

from __future__ import annotations

import io
import json
import sys
from pathlib import Path

import pytest

from diffctl.launch.actions import GroupAction
from diffctl.launch_ros.actions import (
    Node,
    PushRosNamespace,
    SetParameter,
    SetParametersFromFile,
    SetRemap,
    SetROSLogDir,
)
from diffctl.launch_ros.descriptions import ParameterFile

from .conftest import DATA, run

XML = """
<launch>
  <group scoped="true">
    <push-ros-namespace namespace="robot"/>
    <set_parameter name="use_sim_time" value="true"/>
    <set_parameters_from_file filename="{scope}"/>
    <set_remap from="/tf" to="tf"/>
    <set_ros_log_dir new_log_dir="{logs}"/>
    <node exec="{python}" args="{echo}" name="talker" namespace="ns" ros_args="--log-level debug">
      <env name="ECHO_TO" value="{out}"/>
      <param name="rate_hz" value="10"/>
      <param name="wheels">
        <param name="radius_m" value="0.04"/>
        <param name="names" value="l, r" value-sep=", "/>
      </param>
      <param name="frame" value="base" type="str"/>
      <param from="{own}"/>
      <remap from="chatter" to="/chat"/>
    </node>
  </group>
</launch>
"""

YAML = """
launch:
- group:
    scoped: 'true'
    children:
    - push_ros_namespace: {{namespace: robot}}
    - set_parameter: {{name: use_sim_time, value: 'true'}}
    - set_parameters_from_file: {{filename: '{scope}'}}
    - set_remap: {{from: /tf, to: tf}}
    - set_ros_log_dir: {{new_log_dir: '{logs}'}}
    - node:
        exec: '{python}'
        args: '{echo}'
        name: talker
        namespace: ns
        ros_args: --log-level debug
        env: [{{name: ECHO_TO, value: '{out}'}}]
        param:
        - {{name: rate_hz, value: 10}}
        - name: wheels
          param:
          - {{name: radius_m, value: 0.04}}
          - {{name: names, value: [l, r]}}
        - {{name: frame, value: base, type: str}}
        - {{from: '{own}'}}
        remap: [{{from: chatter, to: /chat}}]
"""


def python_entities(paths: dict[str, str]) -> list:
    return [
        GroupAction(
            [
                PushRosNamespace("robot"),
                SetParameter("use_sim_time", True),
                SetParametersFromFile(paths["scope"]),
                SetRemap("/tf", "tf"),
                SetROSLogDir(paths["logs"]),
                Node(
                    executable=sys.executable,
                    arguments=[paths["echo"]],
                    name="talker",
                    namespace="ns",
                    ros_arguments=["--log-level", "debug"],
                    additional_env={"ECHO_TO": paths["out"]},
                    parameters=[
                        {"rate_hz": 10},
                        {"wheels": {"radius_m": 0.04, "names": ["l", "r"]}},
                        {"frame": "base"},
                        ParameterFile(paths["own"]),
                    ],
                    remappings=[("chatter", "/chat")],
                ),
            ],
            scoped=True,
        )
    ]


def parsed_entities(text: str, suffix: str) -> list:
    from diffctl.launch.frontend import Parser

    stream = io.StringIO(text)
    stream.name = f"test.launch.{suffix}"
    root, parser = Parser.load(stream)
    return [parser.parse_description(root)]


def received(out: Path) -> dict:
    """What the node got, with each parameter file's path replaced by what it holds (the names of the files
    launch writes differ from run to run)."""
    seen = json.loads(out.read_text())
    files = seen.pop("params_files")
    written = {path: content for path, content in files.items() if Path(path).name.startswith("launch_params_")}
    seen["argv"] = [written.get(word, word) for word in seen["argv"]]
    return seen


@pytest.fixture
def paths(tmp_path: Path) -> dict[str, str]:
    scope, own = tmp_path / "scope.yaml", tmp_path / "own.yaml"
    scope.write_text("/**:\n  ros__parameters:\n    from_scope: 1\n")
    own.write_text("/robot/ns/talker:\n  ros__parameters:\n    from_file: 2\n")
    return {"scope": str(scope), "own": str(own), "logs": str(tmp_path / "logs"), "echo": str(DATA / "echo_args.py"),
            "python": sys.executable, "out": str(tmp_path / "out.json")}  # fmt: skip


def test_xml_yaml_and_python_start_the_same_node(paths: dict[str, str]) -> None:
    results = {}
    for frontend, make in (
        ("python", lambda: python_entities(paths)),
        ("xml", lambda: parsed_entities(XML.format(**paths), "xml")),
        ("yaml", lambda: parsed_entities(YAML.format(**paths), "yaml")),
    ):
        code, _ = run(make())
        assert code == 0, frontend
        results[frontend] = received(Path(paths["out"]))
    assert results["xml"] == results["python"]
    assert results["yaml"] == results["python"]
    assert results["python"]["ros_log_dir"] == paths["logs"]
    assert results["python"]["argv"] == [
        "--ros-args", "--log-level", "debug",
        "--ros-args", "-r", "__node:=talker", "-r", "__ns:=/robot/ns",
        "-p", "use_sim_time:=True", "--params-file", paths["scope"],
        "--params-file", {"/robot/ns/talker": {"ros__parameters": {"rate_hz": 10}}},
        "--params-file",
        {"/robot/ns/talker": {"ros__parameters": {"wheels.radius_m": 0.04, "wheels.names": ["l", "r"]}}},
        "--params-file", {"/robot/ns/talker": {"ros__parameters": {"frame": "base"}}},
        "--params-file", paths["own"],
        "-r", "/tf:=tf", "-r", "chatter:=/chat",
    ]  # fmt: skip


@pytest.mark.parametrize(
    ("text", "suffix"),
    [
        ('<launch><node exec="true"><param name="x" value="1" from="f.yaml"/></node></launch>', "xml"),
        ("launch:\n- node: {exec: 'true', param: [{name: x}]}\n", "yaml"),
    ],
)
def test_a_malformed_param_is_refused_when_parsed(text: str, suffix: str) -> None:
    with pytest.raises((RuntimeError, ValueError), match=r"mutually exclusive|either a value attribute"):
        parsed_entities(text, suffix)
