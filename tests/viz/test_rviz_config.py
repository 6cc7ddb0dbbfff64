"""RViz config files and the visualizer's parameters: what is read, and how bad values are reported."""

from __future__ import annotations

from pathlib import Path

import pytest

from diffctl.errors import ConfigError, ParameterError
from diffctl.viz.rviz_config import default_config, load_rviz, parse_rviz
from diffctl.viz.settings import VizSettings

REPO = Path(__file__).resolve().parents[2]


def test_shipped_diffbot_rviz() -> None:
    c = load_rviz(REPO / "config" / "diffbot.rviz")
    assert c.fixed_frame == "odom" and c.ignored == ()
    kinds = {d.kind: d for d in reversed(c.displays)}  # the first display of each kind
    assert set(kinds) == {"grid", "robot_model", "tf", "odometry", "laser_scan", "image"}
    assert kinds["robot_model"].topic == "/robot_description"
    assert kinds["odometry"].topic == "/diffbot_base_controller/odom" and kinds["odometry"].color_rgb == (255, 25, 0)
    assert c.topics("odometry") == ["/diffbot_base_controller/odom", "/odom"]  # /odom: the earlier variant
    assert kinds["laser_scan"].topic == "/scan" and kinds["image"].topic == "/camera/image_raw"
    assert c.to_json()["displays"][0]["color"] == "#a0a0a4"
    assert [d.kind for d in default_config().displays] == [d.kind for d in c.displays]


def test_topic_forms_groups_and_ignored_classes() -> None:
    text = """
Visualization Manager:
  Global Options: {Fixed Frame: /map, Frame Rate: 10}
  Displays:
    - Class: rviz_common/Group
      Enabled: false
      Name: sensors
      Displays:
        - {Class: rviz_default_plugins/LaserScan, Name: front, Topic: front_scan}
        - {Class: rviz_default_plugins/MarkerArray, Name: m}
    - {Class: rviz_default_plugins/Odometry, Name: o, Topic: {Value: /odom, Depth: 5}, Keep: 7}
    - {Class: rviz_default_plugins/MarkerArray, Name: m2}
    - {Class: rviz_default_plugins/Camera, Name: cam, Topic: {Value: /cam/image}}
"""
    c = parse_rviz(text, "x.rviz")
    assert c.fixed_frame == "map" and c.frame_rate_hz == 10
    scan, odom, cam = c.displays
    assert scan.topic == "/front_scan" and scan.enabled is False  # a disabled group disables its children
    assert odom.topic == "/odom" and odom.keep == 7 and cam.kind == "image" and cam.topic == "/cam/image"
    assert c.ignored == ("rviz_default_plugins/MarkerArray",)  # listed once
    assert c.topics("laser_scan") == [] and c.topics("odometry") == ["/odom"]


@pytest.mark.parametrize(
    ("text", "where"),
    [
        ("Visualization Manager:\n  Displays: [\n", "x.rviz:3:1"),
        ("Panels: []\n", "no 'Visualization Manager'"),
        ("Visualization Manager:\n  Displays: {a: 1}\n", "Visualization Manager.Displays: must be a list"),
        ("Visualization Manager:\n  Displays:\n    - {Name: x}\n", "Displays[0]: display has no 'Class'"),
        (
            "Visualization Manager:\n  Displays:\n    - {Class: rviz_default_plugins/Grid, Color: '1; 2'}\n",
            "Displays[0].Color: must be a colour",
        ),
        ("Visualization Manager:\n  Global Options: {Fixed Frame: 'a b'}\n", "Fixed Frame: must be a frame name"),
        (
            "Visualization Manager:\n  Displays:\n    - {Class: rviz_default_plugins/Odometry, Keep: -3}\n",
            "Displays[0].Keep: must be a number in [0, 100000], got -3",
        ),
        (
            "Visualization Manager:\n  Displays:\n    - {Class: rviz_default_plugins/LaserScan, Topic: 'a b'}\n",
            "Displays[0].Topic: is not a valid topic name",
        ),
    ],
)
def test_malformed_files_name_file_and_field(text: str, where: str) -> None:
    with pytest.raises(ConfigError) as e:
        parse_rviz(text, "x.rviz")
    assert where in str(e.value) and str(e.value).startswith("x.rviz")


def test_settings_from_ros_params_and_options() -> None:
    s = VizSettings.from_params({"use_sim_time": True, "max_linear_mps": 2, "unrelated": 1}, port=0)
    assert s.use_sim_time is True and s.max_linear_mps == 2.0 and s.port == 0 and s.host == "127.0.0.1"
    assert VizSettings.from_params({"use_sim_time": "false"}).use_sim_time is False
    for params, field in (
        ({"port": 70000}, "port"),
        ({"max_angular_radps": float("nan")}, "max_angular_radps"),
        ({"teleop_topic": "bad topic"}, "teleop_topic"),
        ({"use_sim_time": 3}, "use_sim_time"),
        ({"frame_rate_hz": "fast"}, "frame_rate_hz"),
    ):
        with pytest.raises(ParameterError) as e:
            VizSettings.from_params(params)
        assert e.value.field == field and repr(next(iter(params.values())))[:5] in str(e.value)
