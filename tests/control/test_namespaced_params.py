"""Parameter files for namespaced controller managers, as rcl and controller_manager's spawner read them."""

from __future__ import annotations

from pathlib import Path

from diffctl.control.params import controller_node_params, load_manager_files, manager_params, section_type

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


def test_each_robot_takes_its_own_section(tmp_path: Path) -> None:
    f = tmp_path / "robots.yaml"
    f.write_text(PER_ROBOT)
    assert load_manager_files([str(f)], "/robot1/controller_manager")["update_rate"] == 10
    assert load_manager_files([str(f)], "/robot2/controller_manager")["update_rate"] == 40
    for ns, radius in (("/robot1", 0.1), ("/robot2", 0.2)):
        params = manager_params({}, params_files=(str(f),), namespace=ns)
        assert controller_node_params("ctrl", params)["wheel_radius"] == radius


def test_bare_keys_reach_the_root_namespace_only_and_wildcards_every_robot() -> None:
    assert load_manager_files([TUTORIAL], "/controller_manager")["update_rate"] == 20
    assert load_manager_files([TUTORIAL], "/robot1/controller_manager") == {}
    assert load_manager_files([FLEET], "/robot3/controller_manager")["update_rate"] == 20
    params = manager_params({}, params_files=(FLEET,), namespace="/robot3")
    assert controller_node_params("diffbot_base_controller", params)["wheel_radius"] == 0.04


def test_the_spawner_finds_a_type_as_jazzys_spawner_does() -> None:
    said: list[str] = []
    assert section_type(TUTORIAL, "diffbot_base_controller") == "diff_drive_controller/DiffDriveController"
    assert section_type(TUTORIAL, "diffbot_base_controller", "/robot1", said.append) is None
    assert said == ["Missing namespace : /robot1 or wildcard in parameter file for controller : "
                    "diffbot_base_controller"]
    assert section_type(FLEET, "diffbot_base_controller", "/robot1") == "diff_drive_controller/DiffDriveController"


def test_the_managers_own_arguments_reach_its_controllers(tmp_path: Path) -> None:
    # rclcpp: the process's --ros-args are every node's; a controller's params_file is its own (local) layer.
    from diffctl import ros_args

    own = tmp_path / "own.yaml"
    own.write_text("ctrl:\n  ros__parameters:\n    wheel_radius: 0.3\n")
    process = ros_args.parse(["--params-file", FLEET, "-p", "ctrl:wheel_radius:=0.2", "-p", "publish_rate:=5.0"],
                             "controller_manager").overrides
    params = manager_params({"ctrl.params_file": [str(own)]}, params_files=(FLEET,), overrides=process)
    got = controller_node_params("ctrl", params)
    assert (got["wheel_radius"], got["publish_rate"]) == (0.3, 5.0)
    bare = manager_params({}, params_files=(FLEET,), overrides=process)
    assert controller_node_params("ctrl", bare)["wheel_radius"] == 0.2
