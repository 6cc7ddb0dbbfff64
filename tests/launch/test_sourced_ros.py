"""diffctl's launcher loads Python launch files with its own `launch` even where a sourced ROS 2 comes first."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

LAUNCH_FILE = """
from launch import LaunchDescription
from launch.actions import ExecuteProcess
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        ExecuteProcess(cmd=['sh', '-c', 'echo hello'], name='greeter'),
        Node(package='demo_nodes_py', executable='talker'),
    ])
"""


def test_a_sourced_ros_launch_does_not_replace_diffctls_engine(tmp_path: Path) -> None:
    site = tmp_path / "opt_ros" / "site-packages"
    for name in ("launch", "launch_ros"):
        (site / name).mkdir(parents=True)
        (site / name / "__init__.py").write_text("raise ImportError('the sourced ROS module was imported')\n")
    (tmp_path / "demo.launch.py").write_text(LAUNCH_FILE)
    env = {**os.environ, "PYTHONPATH": str(site)}
    out = subprocess.run([sys.executable, "-m", "diffctl", "launch", "--print", str(tmp_path / "demo.launch.py")],
                         env=env, capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "echo hello" in out.stdout and "talker" in out.stdout, out.stdout
