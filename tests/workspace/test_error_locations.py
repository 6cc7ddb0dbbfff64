"""Errors in files reached through a package's share directory (diffctl's symlink tree in the cache) name the
user's source file under src/, which is the one to edit."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from diffctl.description.robot_files import load_description
from diffctl.errors import DescriptionError, yaml_error
from diffctl.source_paths import user_source
from diffctl.workspace import share_dir
from tests.workspace.conftest import package_xml, write_tree

CMAKE = """cmake_minimum_required(VERSION 3.8)
project(my_bot)
find_package(ament_cmake REQUIRED)
install(DIRECTORY launch config urdf DESTINATION share/${PROJECT_NAME})
ament_package()
"""

LAUNCH = """from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from ament_index_python.packages import get_package_share_directory


def generate_launch_description():
    return LaunchDescription([
        IncludeLaunchDescription(PythonLaunchDescriptionSource(
            get_package_share_directory('gazebo_ros') + '/launch/gazebo.launch.py')),
    ])
"""

URDF = (
    '<robot name="bot">\n<link name="a"/>\n'
    '<joint name="j" type="hinge"><parent link="a"/><child link="b"/></joint>\n</robot>\n'
)


@pytest.fixture
def ws(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    root = tmp_path / "ws"
    write_tree(
        root / "src" / "my_bot",
        {
            "package.xml": package_xml("my_bot"),
            "CMakeLists.txt": CMAKE,
            "launch/sim.launch.py": LAUNCH,
            "config/bad.yaml": "a: 1\nb: [2\n",
            "urdf/bot.urdf": URDF,
        },
    )
    monkeypatch.chdir(root)
    return root


def test_errors_in_share_files_name_the_source(ws: Path) -> None:
    share = share_dir("my_bot")
    src = ws / "src" / "my_bot"
    assert not str(share).startswith(str(src))  # reached through the cache, as launch files reach it
    with pytest.raises(DescriptionError) as e:
        load_description(share / "urdf" / "bot.urdf")
    assert str(e.value).startswith(f"{src / 'urdf' / 'bot.urdf'}:3"), str(e.value)
    import yaml

    try:
        yaml.safe_load((share / "config" / "bad.yaml").read_text())
    except yaml.YAMLError as err:
        located = yaml_error(err, str(share / "config" / "bad.yaml"))
    assert str(located).startswith(f"{src / 'config' / 'bad.yaml'}:"), str(located)
    # paths elsewhere, generated files of the cache and "<string>" sources are left as they are
    assert user_source("<string>") == "<string>" and user_source("/etc/hosts") == "/etc/hosts"
    marker = share.parent / "ament_index" / "resource_index" / "packages" / "my_bot"
    assert user_source(str(marker)) == str(marker)


def test_launch_error_names_the_source_launch_file(ws: Path) -> None:
    r = subprocess.run(
        [sys.executable, "-m", "diffctl", "launch", "my_bot", "sim.launch.py"],
        capture_output=True, text=True, timeout=120, cwd=ws, env={**os.environ},
    )
    assert r.returncode == 2, r.stdout + r.stderr
    assert f"{ws / 'src/my_bot/launch/sim.launch.py'}:10: package 'gazebo_ros' not found" in r.stderr, r.stderr
    assert "/.cache/" not in r.stderr and "cache/diffctl/workspaces" not in r.stderr
