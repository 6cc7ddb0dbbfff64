"""Actions and lifecycle nodes agree with the real rclpy: the same programs (tests/client/programs) run on
Jazzy's rclpy with Fast DDS (the oracle venv) and on diffctl's client library over a real Zenoh router,
and must print the same observations line for line."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from tests.oracle import jazzy_venv

PROGRAMS = Path(__file__).resolve().parent / "programs"
OVERLAY = Path(__file__).resolve().parents[2] / "diffctl" / "overlay"


def run_ours(program: Path) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith(("ROS_", "AMENT_", "COLCON_"))}
    env["PYTHONPATH"] = str(OVERLAY)
    with tempfile.TemporaryDirectory() as cwd:
        return subprocess.run([sys.executable, str(program)], env=env, cwd=cwd, capture_output=True, text=True,
                              timeout=90)


def run_both(name: str) -> tuple[subprocess.CompletedProcess[str], subprocess.CompletedProcess[str]]:
    program = PROGRAMS / name
    real = jazzy_venv.run_python(program.read_text(), timeout_s=90)
    ours = run_ours(program)
    assert ours.returncode == 0, ours.stdout + ours.stderr
    return real, ours


def _unstamped(stderr: str) -> str:
    return re.sub(r"^\[(\w+)\] \[\d+\.\d{9}\] ", r"[\1] ", stderr, flags=re.MULTILINE)


@pytest.mark.usefixtures("router")
def test_actions_goal_feedback_result_cancel_agree() -> None:
    real, ours = run_both("action_fibonacci.py")
    assert ours.stdout.splitlines() == real.stdout.splitlines()
    assert "result 4 [0, 1, 1, 2, 3, 5]" in ours.stdout  # the program ran to its end on both
    assert "feedback after shutdown rclpy._rclpy_pybind11 RCLError Failed to publish feedback with an action " \
        "server: feedback publisher is invalid" in ours.stdout
    assert "wait_for_server after shutdown RCLError Failed to check if action server is available: rcl node's " \
        "context is invalid" in ours.stdout
    # The server logs through its `action_server` child logger (the line a user's log filter or
    # --log-level late_server.action_server:=... picks)
    for text in ("[ERROR] [late_server.action_server]: Error raised in execute callback: gave up",
                 "[WARN] [late_server.action_server]: Goal state not set, assuming aborted. Goal ID: [",
                 # its abort's status could not go out: the execute task's error, reported when it is collected
                 "The following exception was never retrieved: Failed get goal status array: feedback publisher "
                 "is invalid, at /project/src/rcl_action/action_server.c:984"):
        assert text in _unstamped(real.stderr) and text in _unstamped(ours.stderr), text


@pytest.mark.usefixtures("router")
def test_lifecycle_transitions_services_and_events_agree() -> None:
    real, ours = run_both("lifecycle_node.py")
    assert ours.stdout.splitlines() == real.stdout.splitlines()
    assert "configure raising TransitionCallbackReturnType.ERROR (4, 'finalized')" in ours.stdout
    for text in ("[rcl_lifecycle]: No transition matching 4 found for current state inactive",
                 "[rcl_lifecycle]: No transition matching fly found for current state inactive"):
        assert text in real.stderr and text in ours.stderr
