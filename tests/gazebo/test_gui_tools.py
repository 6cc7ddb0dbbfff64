"""GUI-only tools in launch files: a counterpart where diffctl has one, else a stand-in that warns once and
idles until the launch stops it (so OnProcessExit handlers do not fire early)."""

from __future__ import annotations

import os
import signal
import subprocess

from diffctl.workspace.gui_tools import argv_for
from diffctl.workspace.package_index import executable_argv
from tests.conftest import free_port


def test_rqt_tools_get_a_stand_in_that_warns_once_and_waits(procs) -> None:
    argv = executable_argv("rqt_plot", "rqt_plot")
    assert argv == argv_for("rqt_plot", "rqt_plot")
    p = procs.start([*argv, "--ros-args", "-r", "__node:=plot"], stderr=subprocess.PIPE, stdout=subprocess.PIPE)
    line = p.stderr.readline()
    assert "rqt_plot/rqt_plot is a GUI-only tool diffctl does not provide; skipped" in line
    assert p.poll() is None  # still there: the launch decides when it ends
    assert procs.stop(p, signal.SIGINT) == 0
    assert p.stderr.read() == ""  # said once


def test_counterparts_start_diffctls_component_with_the_launchs_arguments() -> None:
    argv = executable_argv("joint_state_publisher_gui", "joint_state_publisher_gui")
    out = subprocess.run([*argv, "--help"], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0 and "Usage: diffctl joint-state-publisher" in out.stdout
    assert "runs as diffctl's counterpart" in out.stderr
    steering = executable_argv("rqt_robot_steering", "rqt_robot_steering")
    assert steering[-1] == "viz --port 0"
    assert argv_for("robot_state_publisher", "robot_state_publisher") is None


def test_a_tools_own_arguments_do_not_reach_a_counterpart_that_does_not_take_them() -> None:
    from diffctl.workspace.gui_tools import ros_args_only

    # ros_gz_sim_demos' imu.launch.py: Node(package='rqt_topic', executable='rqt_topic', arguments=['-t'])
    assert ros_args_only(["-t", "--ros-args", "-r", "__node:=rqt_topic", "--", "x"]) == [
        "--ros-args",
        "-r",
        "__node:=rqt_topic",
    ]
    argv = executable_argv("rqt_topic", "rqt_topic")
    env = {**os.environ, "DIFFCTL_ROUTER": f"tcp/127.0.0.1:{free_port()}"}  # no router: it stops after parsing
    out = subprocess.run([*argv, "-t"], capture_output=True, text=True, timeout=60, env=env)
    # past its arguments, the visualizer's node looks for the router
    assert "No such option" not in out.stderr and "no Zenoh router answers" in out.stderr, out.stderr


def test_gz_sim_gui_client_idles_with_one_warning(procs) -> None:
    import sys

    p = procs.start(
        [sys.executable, "-c", "from diffctl.gz.cli import main; main()", "sim", "-g", "-v", "4"],
        stderr=subprocess.PIPE,
        stdout=subprocess.PIPE,
    )
    assert "gz sim -g starts Gazebo's GUI client" in p.stderr.readline()
    assert p.poll() is None
    assert procs.stop(p, signal.SIGTERM) == 0
