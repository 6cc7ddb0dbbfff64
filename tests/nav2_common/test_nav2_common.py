"""nav2_common's launch helpers as robot projects' launch files use them (`from nav2_common.launch import …`):
the values are nav2_common's documented rewrites (Jazzy), worked out by hand for these files."""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import pytest
import yaml
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration, SubstitutionFailure
from nav2_common.launch import HasNodeParams, ParseMultiRobotPose, ReplaceString, RewrittenYaml

from launch import LaunchContext

PARAMS = """\
controller_server:
  ros__parameters:
    use_sim_time: false
    robot_base_frame: base_link
    FollowPath:
      plugin: dwb_core::DWBLocalPlanner
      max_vel_x: 0.26
    speeds: [0.1, 0.2, 0.3]
amcl:
  ros__parameters:
    use_sim_time: false
"""


@pytest.fixture
def context(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> LaunchContext:
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))  # the copies they write land here
    ctx = LaunchContext()
    ctx.launch_configurations.update({"ns": "robot1", "sim": "True", "frame": "base_footprint"})
    return ctx


def written(path: str) -> object:
    return yaml.safe_load(Path(path).read_text())


def test_rewritten_yaml_sets_names_paths_and_keys_and_nests_the_whole(tmp_path: Path, context: LaunchContext) -> None:
    source = tmp_path / "nav2_params.yaml"
    source.write_text(PARAMS)
    rewrites = {
        "use_sim_time": LaunchConfiguration("sim"),  # a bare name: every key so named, at any depth
        "robot_base_frame": LaunchConfiguration("frame"),
        "controller_server.ros__parameters.FollowPath.max_vel_x": "0.5",  # a dotted path of a leaf
        "controller_server.ros__parameters.speeds.1": "7",  # a list item by its index
        "bt_navigator.ros__parameters.enable_groot": "false",  # absent, through ros__parameters: added
        "not.a.parameter": "1",  # absent, not through ros__parameters: left out
    }
    typed = RewrittenYaml(source_file=str(source), param_rewrites=rewrites, root_key=LaunchConfiguration("ns"),
                          key_rewrites={"FollowPath": "FollowPathDWB"}, convert_types=True)  # fmt: skip
    assert written(typed.perform(context)) == {
        "robot1": {
            "controller_server": {"ros__parameters": {
                "use_sim_time": True, "robot_base_frame": "base_footprint",
                "FollowPathDWB": {"plugin": "dwb_core::DWBLocalPlanner", "max_vel_x": 0.5},
                "speeds": [0.1, 7, 0.3]}},
            "amcl": {"ros__parameters": {"use_sim_time": True}},
            "bt_navigator": {"ros__parameters": {"enable_groot": False}},
        }
    }  # fmt: skip
    # without convert_types only true/false change type; an empty root key nests nothing
    text = RewrittenYaml(str(source), {"max_vel_x": "0.5", "use_sim_time": "TRUE"}, root_key="")
    out = written(text.perform(context))
    follow = out["controller_server"]["ros__parameters"]["FollowPath"]
    assert follow["max_vel_x"] == "0.5" and out["amcl"]["ros__parameters"]["use_sim_time"] is True
    assert yaml.safe_load(PARAMS) == yaml.safe_load(source.read_text())  # the source is left as it was


def test_replace_string_copies_the_file_with_the_strings_replaced(tmp_path: Path, context: LaunchContext) -> None:
    source = tmp_path / "bridge.yaml"
    source.write_text("- ros_topic_name: <namespace>/cmd_vel\n  gz_topic_name: /model/<model>//cmd_vel\n")
    swap = {"<namespace>": LaunchConfiguration("ns"), "<model>": "rover", "//": "/"}
    copy = ReplaceString(source_file=str(source), replacements=swap).perform(context)
    assert copy != str(source)
    assert Path(copy).read_text() == "- ros_topic_name: robot1/cmd_vel\n  gz_topic_name: /model/rover/cmd_vel\n"
    off = ReplaceString(str(source), swap, condition=IfCondition("false"))
    assert off.perform(context) == str(source)  # a false condition: the file itself
    missing = ReplaceString(str(tmp_path / "nope.yaml"), swap)
    with pytest.raises(SubstitutionFailure, match=r"nope\.yaml"):
        missing.perform(context)


def test_has_node_params_and_multirobot_poses(tmp_path: Path, context: LaunchContext,
                                              monkeypatch: pytest.MonkeyPatch) -> None:  # fmt: skip
    source = tmp_path / "nav2_params.yaml"
    source.write_text(PARAMS)
    assert HasNodeParams(str(source), "amcl").perform(context) == "True"
    assert HasNodeParams(str(source), "docking_server").perform(context) == "False"
    argv = ["ros2", "launch", "nav2_bringup", "multi.py",
            'robots:=robot1={x: 1.0, y: -2.0, yaw: 1.5707}; robot2={x: 3.0, z: 0.1}; broken', "use_rviz:=False"]
    monkeypatch.setattr(sys, "argv", argv)
    zero = dict.fromkeys(("x", "y", "z", "roll", "pitch", "yaw"), 0.0)
    assert ParseMultiRobotPose("robots").value() == {
        "robot1": {**zero, "x": 1.0, "y": -2.0, "yaw": 1.5707},
        "robot2": {**zero, "x": 3.0, "z": 0.1},
    }
    assert ParseMultiRobotPose("other").value() == {}
