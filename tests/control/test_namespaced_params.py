"""Parameter files for namespaced controller managers, as rcl and controller_manager's spawner read them: the
controllers' real client nodes, made with the arguments controller_manager gives them."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from diffctl.control.controller_node import controller_node_arguments, make_controller_node
from diffctl.control.controllers.param_decl import overrides
from diffctl.control.params import load_manager_files, section_type

pytestmark = pytest.mark.usefixtures("client_bus")

REPO = Path(__file__).resolve().parents[2]
TUTORIAL = str(REPO / "config" / "diff_drive_controller.yaml")
FLEET = str(REPO / "config" / "fleet_controllers.yaml")

PER_ROBOT = """
/robot1/controller_manager:
  ros__parameters:
    update_rate: 10
    ctrl:
      type: diff_drive_controller/DiffDriveController
/robot2/controller_manager:
  ros__parameters:
    update_rate: 40
/robot1/ctrl:
  ros__parameters:
    wheel_radius: 0.1
/robot2/ctrl:
  ros__parameters:
    wheel_radius: 0.2
"""


def controller_params(name: str, namespace: str, manager_arguments: list[str], params_files: tuple[str, ...] = (),
                      use_sim_time: bool = False) -> dict[str, Any]:
    """What a controller's node gets, as the manager makes it."""
    arguments = controller_node_arguments(manager_arguments, params_files, use_sim_time)
    node = make_controller_node(name, namespace, arguments)
    try:
        return overrides(node)
    finally:
        node.destroy_node()


def test_each_robot_takes_its_own_section(tmp_path: Path) -> None:
    f = tmp_path / "robots.yaml"
    f.write_text(PER_ROBOT)
    assert load_manager_files([str(f)], "/robot1/controller_manager")["update_rate"] == 10
    assert load_manager_files([str(f)], "/robot2/controller_manager")["update_rate"] == 40
    for ns, radius in (("/robot1", 0.1), ("/robot2", 0.2)):
        assert controller_params("ctrl", ns, ["--ros-args", "--params-file", str(f)])["wheel_radius"] == radius


def test_bare_keys_reach_the_root_namespace_only_and_wildcards_every_robot() -> None:
    assert load_manager_files([TUTORIAL], "/controller_manager")["update_rate"] == 20
    assert load_manager_files([TUTORIAL], "/robot1/controller_manager") == {}
    assert load_manager_files([FLEET], "/robot3/controller_manager")["update_rate"] == 20
    got = controller_params("diffbot_base_controller", "/robot3", ["--ros-args", "--params-file", FLEET])
    assert got["wheel_radius"] == 0.04


def test_the_spawner_finds_a_type_as_jazzys_spawner_does() -> None:
    said: list[str] = []
    assert section_type(TUTORIAL, "diffbot_base_controller") == "diff_drive_controller/DiffDriveController"
    assert section_type(TUTORIAL, "diffbot_base_controller", "/robot1", said.append) is None
    assert said == ["Missing namespace : /robot1 or wildcard in parameter file for controller : "
                    "diffbot_base_controller"]
    assert section_type(FLEET, "diffbot_base_controller", "/robot1") == "diff_drive_controller/DiffDriveController"


def test_the_managers_own_arguments_reach_its_controllers(tmp_path: Path) -> None:
    # controller_manager: the manager node's arguments, then the controller's params_file (later wins), then
    # use_sim_time; `__node`/`__ns` rules stay the manager's.
    own = tmp_path / "own.yaml"
    own.write_text("ctrl:\n  ros__parameters:\n    wheel_radius: 0.3\n")
    manager = ["--ros-args", "--params-file", FLEET, "-p", "ctrl:wheel_radius:=0.2", "-p", "publish_rate:=5.0",
               "-r", "__node:=my_cm", "-r", "__ns:=/robot9"]
    got = controller_params("ctrl", "/", manager, (str(own),), use_sim_time=True)
    assert (got["wheel_radius"], got["publish_rate"], got["use_sim_time"]) == (0.3, 5.0, True)
    assert controller_params("ctrl", "/", manager)["wheel_radius"] == 0.2
    assert "__node" not in " ".join(controller_node_arguments(manager))
