"""Example programs in the style of ros2/examples and ros2/demos (tests/client/examples/py_examples, an
ament_python package copied into a temporary workspace) run unmodified under `diffctl run` and from launch
files: an action server/client pair, a lifecycle talker driven through its services, a tf2 broadcaster and
listener, and a scan → cmd_vel node driving the simulated car of sim_control."""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.conftest import Procs
from tests.e2e.conftest import stack_env  # noqa: F401 (the fixture of a launch on its own router port)
from tests.waiting import lines_until

EXAMPLES = Path(__file__).resolve().parent / "examples" / "py_examples"
SEC = 1_000_000_000


@pytest.fixture
def ws(tmp_path: Path) -> Path:
    root = tmp_path / "ws"
    shutil.copytree(EXAMPLES, root / "src" / "py_examples")
    return root


def env() -> dict[str, str]:
    # The workspace is the one enclosing the current directory, as for a user in ~/ros2_ws.
    # ROS_DOMAIN_ID stays: a user's shell may export one, and the stack the nodes join was started in it.
    e = {k: v for k, v in os.environ.items()
         if k == "ROS_DOMAIN_ID" or not k.startswith(("ROS_", "AMENT_", "COLCON_", "DIFFCTL_WORK"))}
    e["PYTHONUNBUFFERED"] = "1"
    return e


# How long a stop may take before the test calls it hung and SIGKILLs: a failure bound only. A launch stops its
# children with SIGINT and escalates after 5 s itself; on a loaded machine a clean stop took longer than the
# 5 s Procs.stop allows by default, and the launch's SIGKILL exit (-9) failed the test.
STOP_BOUND_S = 30.0

def diffctl(procs: Procs, ws: Path, *args: str) -> subprocess.Popen:
    return procs.start([sys.executable, "-m", "diffctl", *args], cwd=ws, env=env())


def run(ws: Path, *args: str, timeout_s: float = 60) -> subprocess.CompletedProcess[str]:
    """`diffctl ARGS` to its end. Past the failure bound its whole process group is killed (`diffctl run`'s
    node too, which a plain timeout left running) and the failure shows what it printed."""
    p = subprocess.Popen([sys.executable, "-m", "diffctl", *args], cwd=ws, env=env(), stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        out, err = p.communicate(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, err = p.communicate()
        raise AssertionError(f"diffctl {' '.join(args)} did not end within {timeout_s} s:\n{out}{err}") from None
    return subprocess.CompletedProcess(p.args, p.returncode, out, err)


def wait_for_line(p: subprocess.Popen, text: str, timeout_s: float = 60) -> list[str]:
    """Lines of `p` up to the first containing `text` (the process keeps running)."""
    lines, found = lines_until(p.stdout, lambda line: text in line, timeout_s)
    lines = [line.rstrip("\n") for line in lines]
    if not found:
        raise AssertionError(f"{text!r} never came:\n" + "\n".join(lines))
    return lines


@pytest.mark.usefixtures("router")
def test_action_pair_and_tf2_pair_under_diffctl_run(ws: Path, procs: Procs) -> None:
    server = diffctl(procs, ws, "run", "py_examples", "fibonacci_server")
    client = run(ws, "run", "py_examples", "fibonacci_client", "--ros-args", "-p", "order:=6")
    assert client.returncode == 0, client.stdout + client.stderr
    assert "Goal accepted :)" in client.stderr
    assert "Received feedback: array('i', [0, 1, 1, 2, 3, 5, 8])" in client.stderr
    assert "Goal succeeded! Result: array('i', [0, 1, 1, 2, 3, 5, 8])" in client.stderr
    assert procs.stop(server, timeout_s=STOP_BOUND_S) == 0

    broadcaster = diffctl(procs, ws, "run", "py_examples", "tf2_broadcaster")
    listener = run(ws, "run", "py_examples", "tf2_listener", "--ros-args", "-p", "target_frame:=carrot1")
    assert listener.returncode == 0, listener.stdout + listener.stderr
    assert "seen carrot1 in world, radius 2.000" in listener.stdout
    assert procs.stop(broadcaster, timeout_s=STOP_BOUND_S) == 0


@pytest.mark.usefixtures("router")
@pytest.mark.parametrize(("launch_file", "done"), [
    ("actions.launch.py", "Goal succeeded! Result: array('i', [0, 1, 1, 2, 3, 5, 8])"),
    ("lifecycle.launch.py", "[lifecycle_manager] heard True"),
    ("tf2.launch.py", "seen carrot1 in world, radius 2.000"),
])
def test_examples_from_launch_files(ws: Path, procs: Procs, launch_file: str, done: str) -> None:
    launch = diffctl(procs, ws, "launch", "py_examples", launch_file, "--no-router", "--no-color")
    lines = wait_for_line(launch, done)
    assert not [line for line in lines if "Traceback" in line or "[ERROR]" in line], "\n".join(lines)
    if launch_file == "lifecycle.launch.py":
        assert any("[lc_talker]: on_activate() is called." in line for line in lines)
        assert "[lifecycle_manager] state active" in lines
    assert procs.stop(launch, timeout_s=STOP_BOUND_S) == 0


@pytest.mark.slow
@pytest.mark.usefixtures("stack_env")
def test_scan_to_cmd_vel_node_drives_the_simulated_car(ws: Path, procs: Procs, tmp_path: Path) -> None:
    from tests.e2e.stack import Stack

    stack = Stack("sim_control", tmp_path, rtf="2")
    try:
        stack.connect()
        stack.watch_odom("/diffbot_base_controller/odom")
        stack.wait_controllers_active(("diffbot_base_controller", "joint_state_broadcaster"))
        avoider = diffctl(procs, ws, "launch", "py_examples", "avoider.launch.py", "--no-router", "--no-color")
        wait_for_line(avoider, "first scan:")
        start = stack.clock_ns
        deadline = time.monotonic() + 60
        while True:
            last = stack.watch.last(stack.watch.odom)
            if last is not None and last.value[0] > 0.5 and abs(last.value[3] - 0.4) < 0.02:
                break
            assert time.monotonic() < deadline, f"the car did not drive (last odometry: {last})"
            time.sleep(0.05)
        assert last.t_ns - start < 5 * SEC  # 0.4 m/s after a 1 m/s² ramp: well within 5 s of sim time
        assert procs.stop(avoider, signal.SIGINT, timeout_s=STOP_BOUND_S) == 0
    finally:
        stack.kill()
