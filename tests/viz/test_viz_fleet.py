"""Several robots in one page: RobotModel displays with TF prefixes, each robot's odom tree placed in the
world by the simulator's ground truth of the model named like the prefix (as `launch/fleet.launch.py` sets up).
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from diffctl.errors import ConfigError
from diffctl.interfaces import types
from diffctl.viz.rviz_config import parse_rviz
from diffctl.viz.scene import Scene
from diffctl.viz.settings import VizSettings

REPO = Path(__file__).resolve().parents[2]


def fleet_rviz(namespaces: list[str], fixed: str = "world") -> str:
    groups = "\n".join(
        f"""    - Class: rviz_common/Group
      Name: {ns}
      Enabled: true
      Displays:
        - Class: rviz_default_plugins/RobotModel
          Description Topic: {{Value: /{ns}/robot_description}}
          TF Prefix: {ns}
        - Class: rviz_default_plugins/Odometry
          Topic: {{Value: /{ns}/diffbot_base_controller/odom}}"""
        for ns in namespaces
    )
    return f"""Visualization Manager:
  Global Options: {{Fixed Frame: {fixed}}}
  Displays:
    - Class: rviz_default_plugins/TF
{groups}
"""


def tf_msg(*transforms: tuple[str, str, float, float, float]) -> object:
    return types.new("tf2_msgs/msg/TFMessage", {"transforms": [
        {"header": {"frame_id": p}, "child_frame_id": c,
         "transform": {"translation": {"x": x, "y": y}, "rotation": {"z": math.sin(a / 2), "w": math.cos(a / 2)}}}
        for p, c, x, y, a in transforms]})


def gt(name: str, x: float, y: float) -> dict:
    return {"pose": [{"name": name, "position": {"x": x, "y": y}, "orientation": {"w": 1.0}}]}


def centre(points: list[float]) -> tuple[float, float]:
    xs, ys = points[0::2], points[1::2]
    return (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2


def test_two_prefixed_robots_are_drawn_where_the_simulator_has_them() -> None:
    config = parse_rviz(fleet_rviz(["robot1", "robot2"]))
    assert config.robot_models() == [("/robot1/robot_description", "robot1"), ("/robot2/robot_description", "robot2")]
    scene = Scene(config, VizSettings())
    sdf = (REPO / "description" / "my_diff_car_control.sdf").read_text()
    for ns in ("robot1", "robot2"):
        scene.set_robot_description(sdf, f"/{ns}/robot_description")
    # Each robot's own TF: odom → base_footprint (its diff_drive_controller), fixed joints (its RSP).
    scene.on_tf(tf_msg(("robot1/base_footprint", "robot1/base_link", 0, 0, 0),
                       ("robot2/base_footprint", "robot2/base_link", 0, 0, 0)), static=True)
    # robot2 has driven 0.5 m in its own odom; both odoms start where their cars were spawned.
    scene.on_tf(tf_msg(("robot1/odom", "robot1/base_footprint", 0.0, 0.0, 0.0),
                       ("robot2/odom", "robot2/base_footprint", 0.5, 0.0, 0.0)))
    assert scene.frame_view("world")["fixed_known"] is False  # nothing places the odoms yet
    scene.on_ground_truth(gt("robot1", 0.0, 0.0), "robot1")
    scene.on_ground_truth(gt("robot2", 2.0, 1.0), "robot2")

    frame = scene.frame_view("world")
    assert frame["fixed_known"] is True
    assert frame["frames"]["robot2/base_footprint"][:2] == [2.0, 1.0]
    assert frame["frames"]["robot2/odom"][:2] == [1.5, 1.0]  # spawned at x 1.5, driven 0.5
    chassis = {p["link"]: centre(p["pts"]) for p in frame["robot"] if p["link"].endswith("base_link")}
    # The chassis box sits 0.08 m behind base_link (my_diff_car_control.sdf).
    assert chassis["robot1/base_link"] == pytest.approx((-0.08, 0.0), abs=1e-3)
    assert chassis["robot2/base_link"] == pytest.approx((1.92, 1.0), abs=1e-3)
    view = scene.robot_view()
    assert [(r["prefix"], r["name"]) for r in view["robots"]] == [("robot1", "my_diff_car"), ("robot2", "my_diff_car")]


def test_a_bad_tf_prefix_names_the_field() -> None:
    text = fleet_rviz(["robot1"]).replace("TF Prefix: robot1", "TF Prefix: 'robot 1'")
    with pytest.raises(ConfigError, match="TF Prefix"):
        parse_rviz(text, "fleet.rviz")
