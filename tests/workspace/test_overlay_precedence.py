"""A sourced ROS 2 installation wins over diffctl's overlay, in the venv and in every child diffctl starts."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from diffctl.workspace import PYTHON_PATH, use_in_children


def _fake_ros(tmp_path: Path) -> Path:
    """A stand-in for /opt/ros/jazzy/lib/python3.x/site-packages: real-named modules that say who they are."""
    site = tmp_path / "ros" / "site-packages"
    for name in ("rclpy", "launch", "ament_index_python", "std_msgs"):
        (site / name).mkdir(parents=True)
        (site / name / "__init__.py").write_text("SOURCED_ROS = True\n")
    (site / "std_msgs" / "msg").mkdir()
    (site / "std_msgs" / "msg" / "__init__.py").write_text("SOURCED_ROS = True\n")
    return site


def test_overlay_comes_after_a_sourced_ros_on_children_pythonpath(tmp_path: Path) -> None:
    site = _fake_ros(tmp_path)
    env = {"PYTHONPATH": str(site)}
    use_in_children(None, env)
    assert env["PYTHONPATH"].split(":") == [str(site), str(PYTHON_PATH)]
    use_in_children(None, env)  # idempotent: the overlay is never listed twice
    assert env["PYTHONPATH"].split(":") == [str(site), str(PYTHON_PATH)]


def test_child_imports_the_sourced_ros_modules_not_the_overlay(tmp_path: Path) -> None:
    site = _fake_ros(tmp_path)
    env = {"PYTHONPATH": str(site), "PATH": "/usr/bin:/bin"}
    use_in_children(None, env)
    probe = (
        "import rclpy, launch, ament_index_python, std_msgs.msg\n"
        "print(all(getattr(m, 'SOURCED_ROS', False) for m in (rclpy, launch, ament_index_python, std_msgs.msg)))\n"
    )
    out = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True, text=True, timeout=60,
                         cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "True"


def test_without_a_sourced_ros_the_overlay_answers(tmp_path: Path) -> None:
    env = {"PATH": "/usr/bin:/bin"}
    use_in_children(None, env)
    probe = "import rclpy, ament_index_python; print(rclpy.__file__); print(ament_index_python.__file__)"
    out = subprocess.run([sys.executable, "-c", probe], env=env, capture_output=True, text=True, timeout=60,
                         cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert all(line.startswith(str(PYTHON_PATH)) for line in out.stdout.split()), out.stdout
