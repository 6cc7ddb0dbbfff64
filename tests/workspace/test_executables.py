"""`Node(package, executable)`: the user's program, diffctl's component, an installed program — in that order."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

from diffctl.errors import LaunchError
from diffctl.workspace import package_index
from tests.workspace.conftest import package_xml, write_tree
from tests.workspace.test_resolution import install_tree


def program(path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("#!/bin/sh\n")
    path.chmod(0o755)
    return path


def test_the_users_program_then_diffctls_component_then_an_installed_one(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # /opt/ros sourced: real robot_state_publisher and controller_manager programs on AMENT_PREFIX_PATH
    opt = tmp_path / "opt"
    for pkg, exe in (("robot_state_publisher", "robot_state_publisher"), ("controller_manager", "spawner"),
                     ("turtlesim", "turtlesim_node")):
        install_tree(opt, pkg)
        program(opt / "lib" / pkg / exe)
    install_tree(opt, "rmw_zenoh_cpp")  # the real programs join diffctl's graph over it
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(opt))
    monkeypatch.delenv("RMW_IMPLEMENTATION", raising=False)
    ws = tmp_path / "ws"
    write_tree(
        ws / "src" / "controller_manager",
        {
            "package.xml": package_xml("controller_manager"),
            "CMakeLists.txt": "project(controller_manager)\n"
            "install(PROGRAMS scripts/spawner DESTINATION lib/${PROJECT_NAME})\n",
        },
    )
    program(ws / "src/controller_manager/scripts/spawner")
    monkeypatch.chdir(ws)
    *env, spawner = package_index.executable_argv("controller_manager", "spawner")
    assert env[0] == "env" and "RMW_IMPLEMENTATION=rmw_zenoh_cpp" in env
    assert Path(spawner).resolve() == ws / "src/controller_manager/scripts/spawner"  # the user's own
    assert package_index.executable_argv("robot_state_publisher", "robot_state_publisher") == [
        sys.executable, "-m", "diffctl", "robot-state-publisher",
    ]  # diffctl's, not /opt/ros's
    assert package_index.executable_argv("turtlesim", "turtlesim_node")[-1] == str(
        opt / "lib/turtlesim/turtlesim_node"
    )  # a package diffctl does not replace: the installed program
    assert "turtlesim_node" in package_index.executables("turtlesim")


def test_a_missing_executable_names_the_packages_programs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    opt = install_tree(tmp_path / "opt", "tf2_ros")
    program(opt / "lib/tf2_ros/static_transform_publisher")
    monkeypatch.setenv("AMENT_PREFIX_PATH", os.fspath(opt))
    with pytest.raises(LaunchError) as e:
        package_index.executable_argv("tf2_ros", "static_transform_publishr")
    assert "has no executable 'static_transform_publishr' (did you mean 'static_transform_publisher'?)" in str(e.value)
    with pytest.raises(LaunchError, match="unknown package 'tf2_rs'"):
        package_index.executable_argv("tf2_rs", "x")


def test_demo_nodes_yield_to_an_installed_or_workspace_package(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # no demo_nodes anywhere: diffctl's own talker
    assert package_index.executable_argv("demo_nodes_cpp", "talker") == [
        sys.executable, "-m", "diffctl.demo_nodes", "demo_nodes_cpp", "talker",
    ]
    assert {"talker", "listener", "parameter_blackboard"} <= set(package_index.executables("demo_nodes_cpp"))
    # a sourced ROS 2 with the real demo_nodes_cpp: its program
    opt = install_tree(tmp_path / "opt", "demo_nodes_cpp")
    install_tree(opt, "rmw_zenoh_cpp")
    program(opt / "lib/demo_nodes_cpp/talker")
    monkeypatch.setenv("AMENT_PREFIX_PATH", os.fspath(opt))
    assert package_index.executable_argv("demo_nodes_cpp", "talker")[-1] == str(opt / "lib/demo_nodes_cpp/talker")
    with pytest.raises(LaunchError, match="no executable 'talkr'"):
        package_index.executable_argv("demo_nodes_cpp", "talkr")
