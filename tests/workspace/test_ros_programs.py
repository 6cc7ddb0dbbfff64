"""A package diffctl does not provide: the real program from a sourced ROS 2 install joins diffctl's graph over
rmw_zenoh; without an install, one error says what to do. The sourced install is a fake prefix laid out as
ament's (resource index markers, share/<pkg>/package.xml, lib/<pkg>/<exe>)."""

from __future__ import annotations

import os
import subprocess
import sys
import threading
from pathlib import Path
from typing import Any

import pytest

from tests.probe import Probe
from tests.waiting import wait_for
from tests.workspace.conftest import package_xml

LAUNCH = """
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([Node(package='fake_planner', executable='chatter', arguments=['--from-launch'])])
"""
# Stands in for a compiled ROS 2 node: it refuses to run unless started as a real node in diffctl's graph would
# be (RMW_IMPLEMENTATION=rmw_zenoh_cpp), and finds the router only through rmw_zenoh's ZENOH_CONFIG_OVERRIDE.
PROGRAM = """#!/bin/sh
[ "$RMW_IMPLEMENTATION" = rmw_zenoh_cpp ] || { echo "RMW_IMPLEMENTATION=$RMW_IMPLEMENTATION" >&2; exit 3; }
[ "$1" = --from-launch ] || { echo "arguments: $*" >&2; exit 4; }
exec env -u DIFFCTL_ROUTER {python} -m diffctl.demo_nodes demo_nodes_cpp talker
"""


def fake_install(root: Path, *, with_rmw_zenoh: bool) -> Path:
    prefix = root / "opt_ros_jazzy"
    markers = prefix / "share" / "ament_index" / "resource_index" / "packages"
    markers.mkdir(parents=True)
    for name in ["fake_planner"] + (["rmw_zenoh_cpp"] if with_rmw_zenoh else []):
        (markers / name).write_text("")
        (prefix / "share" / name).mkdir(parents=True)
        (prefix / "share" / name / "package.xml").write_text(package_xml(name))
    program = prefix / "lib" / "fake_planner" / "chatter"
    program.parent.mkdir(parents=True)
    program.write_text(PROGRAM.replace("{python}", sys.executable))
    program.chmod(0o755)
    (root / "nav.launch.py").write_text(LAUNCH)
    return prefix


@pytest.mark.slow
def test_a_sourced_ros_program_joins_the_graph_over_rmw_zenoh(router: str, procs, tmp_path: Path,
                                                              monkeypatch: pytest.MonkeyPatch) -> None:
    prefix = fake_install(tmp_path, with_rmw_zenoh=True)
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(prefix))
    monkeypatch.delenv("RMW_IMPLEMENTATION", raising=False)
    launch = procs.diffctl("launch", str(tmp_path / "nav.launch.py"))
    node = Probe("sourced_probe")
    try:
        got: list[Any] = []
        lock = threading.Lock()

        def keep(m: Any) -> None:
            with lock:
                got.append(m.data)

        node.create_subscription("/chatter", "std_msgs/msg/String", keep)
        assert wait_for(lambda: len(got) >= 2, timeout_s=60), (procs.stop(launch), launch.stdout.read())
        assert got[-1].startswith("Hello World: ")
    finally:
        node.close()
    assert procs.stop(launch, timeout_s=20) == 0


def test_without_rmw_zenoh_or_without_the_package_one_error_says_what_to_do(tmp_path: Path) -> None:
    prefix = fake_install(tmp_path, with_rmw_zenoh=False)
    env = {k: v for k, v in os.environ.items() if k != "RMW_IMPLEMENTATION"}

    def launch(ament_prefix_path: str) -> subprocess.CompletedProcess:
        return subprocess.run([sys.executable, "-m", "diffctl", "launch", str(tmp_path / "nav.launch.py")],
                              env={**env, "AMENT_PREFIX_PATH": ament_prefix_path, "DIFFCTL_ROUTER": "tcp/127.0.0.1:9"},
                              capture_output=True, text=True, timeout=120, cwd=tmp_path)

    out = launch(str(prefix))
    assert out.returncode == 2, out.stdout + out.stderr
    text = out.stdout + out.stderr
    assert "fake_planner/chatter" in text and "rmw_zenoh" in text and "ros-jazzy-rmw-zenoh-cpp" in text, text
    assert "Traceback" not in text
    out = launch("")
    assert out.returncode == 2, out.stdout + out.stderr
    text = out.stdout + out.stderr
    assert "unknown package 'fake_planner'" in text and "ros-jazzy-fake-planner" in text, text
    assert "source /opt/ros/jazzy/setup.bash" in text and "Traceback" not in text


def test_a_workspace_c_plus_plus_program_runs_once_built(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from diffctl.errors import LaunchError
    from diffctl.workspace import package_index

    ws = tmp_path / "ws"
    pkg = ws / "src" / "car_control"
    (pkg / "src").mkdir(parents=True)
    (pkg / "package.xml").write_text(package_xml("car_control"))
    (pkg / "CMakeLists.txt").write_text("cmake_minimum_required(VERSION 3.8)\nproject(car_control)\n"
                                        "find_package(rclcpp REQUIRED)\n"
                                        "add_executable(vehicle_controller src/vehicle_controller.cpp)\n"
                                        "install(TARGETS vehicle_controller DESTINATION lib/${PROJECT_NAME})\n")
    monkeypatch.chdir(ws)
    with pytest.raises(LaunchError) as e:
        package_index.executable_argv("car_control", "vehicle_controller")
    text = f"{e.value} {e.value.hint}"
    assert "compiled program" in text and "CMakeLists.txt:4" in text and "colcon build" in text, text
    # colcon built it (isolated layout): the built program runs, in diffctl's graph
    built = ws / "install" / "car_control" / "lib" / "car_control" / "vehicle_controller"
    built.parent.mkdir(parents=True)
    built.write_text("#!/bin/sh\n")
    built.chmod(0o755)
    argv = package_index.executable_argv("car_control", "vehicle_controller")
    assert argv[-1] == str(built) and "RMW_IMPLEMENTATION=rmw_zenoh_cpp" in argv
