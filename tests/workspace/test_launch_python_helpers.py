"""A workspace's Python helper package (installed with `ament_python_install_package`, as nav2_common is) imports
in launch files, with the environment a sourced Jazzy gives (ROS_DISTRO, ROS_VERSION, ROS_PYTHON_VERSION)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

from tests.workspace.conftest import package_xml, write_tree

# A nav2_common-style helper: a Substitution that rewrites a parameter file, written against launch's API
# (perform_substitutions, normalize_to_list_of_substitutions), as Nav2's RewrittenYaml is.
REWRITTEN_YAML = """
import tempfile

import yaml
from launch.substitution import Substitution
from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions


class RewrittenYaml(Substitution):
    def __init__(self, source_file, param_rewrites):
        super().__init__()
        self.__source = normalize_to_list_of_substitutions(source_file)
        self.__rewrites = {k: normalize_to_list_of_substitutions(v) for k, v in param_rewrites.items()}

    def describe(self):
        return ''

    def perform(self, context):
        data = yaml.safe_load(open(perform_substitutions(context, self.__source)))
        params = data['/**']['ros__parameters']
        for key, value in self.__rewrites.items():
            params[key] = perform_substitutions(context, value)
        out = tempfile.NamedTemporaryFile(mode='w', suffix='.yaml', delete=False)
        yaml.safe_dump(data, out)
        return out.name
"""

BRINGUP = """
import os
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, ExecuteProcess, LogInfo
from launch.substitutions import LaunchConfiguration
from my_common.rewritten_yaml import RewrittenYaml

def generate_launch_description():
    here = os.path.dirname(__file__)
    params = RewrittenYaml(os.path.join(here, '..', 'config', 'params.yaml'), {'speed': LaunchConfiguration('speed')})
    return LaunchDescription([
        DeclareLaunchArgument('speed', default_value='1.0'),
        LogInfo(msg='distro ' + os.environ['ROS_DISTRO'] + ' ' + os.environ['ROS_VERSION']),
        ExecuteProcess(cmd=['cat', params], name='show', output='screen'),
        ExecuteProcess(cmd=['sh', '-c', 'echo $ROS_DISTRO $ROS_PYTHON_VERSION; '
                                        'python3 -c "import my_common.rewritten_yaml; print(42)"'],
                       name='child', output='screen'),
    ])
"""


def test_an_ament_python_install_package_helper_imports_in_launch_files_and_children(tmp_path: Path) -> None:
    ws = tmp_path / "ws"
    write_tree(
        ws / "src" / "my_common",
        {
            "package.xml": package_xml("my_common"),
            "CMakeLists.txt": "cmake_minimum_required(VERSION 3.8)\nproject(my_common)\n"
            "find_package(ament_cmake_python REQUIRED)\nament_python_install_package(${PROJECT_NAME})\n"
            "ament_package()\n",
            "my_common/__init__.py": "",
            "my_common/rewritten_yaml.py": REWRITTEN_YAML,
        },
    )
    write_tree(
        ws / "src" / "my_bringup",
        {
            "package.xml": package_xml("my_bringup"),
            "CMakeLists.txt": "project(my_bringup)\n"
            "install(DIRECTORY launch config DESTINATION share/${PROJECT_NAME})\nament_package()\n",
            "launch/bringup.launch.py": BRINGUP,
            "config/params.yaml": "/**:\n  ros__parameters:\n    speed: 0.5\n    name: bot\n",
        },
    )
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_") or k == "ROS_DOMAIN_ID"}
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "diffctl",
            "launch",
            "my_bringup",
            "bringup.launch.py",
            "speed:=2.5",
            "--no-router",
            "--log-dir",
            str(tmp_path / "logs"),
        ],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=ws,
        env=env,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    assert "distro jazzy 2" in done.stdout
    assert re.search(r"\[show\] +speed: '2.5'", done.stdout), done.stdout  # RewrittenYaml ran, rewrote
    assert re.search(r"\[child\] jazzy 3", done.stdout)
    assert re.search(r"\[child\] 42", done.stdout)  # the helper imports in children too
