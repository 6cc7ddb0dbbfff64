"""Helpers for tests that drive a launched sim_control (tests/e2e/stack.py) and inject faults into it."""

from __future__ import annotations

import math
import re
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import psutil

from tests.e2e.stack import Stack

SEC = 1_000_000_000
CMD = "/diffbot_base_controller/cmd_vel"
ODOM = "/diffbot_base_controller/odom"
TWIST_STAMPED = "geometry_msgs/msg/TwistStamped"
CONTROLLERS = ("diffbot_base_controller", "joint_state_broadcaster")
STARTED = re.compile(r"\[([\w.-]+)\]: process started with pid \[(\d+)\]")


def launch_log(stack: Stack) -> str:
    stack._out.flush()
    return stack.log_path.read_text()


def pids(stack: Stack) -> dict[str, int]:
    """The latest pid of every process the launcher started, by name."""
    return {m[1]: int(m[2]) for m in STARTED.finditer(launch_log(stack))}


def wait_until(cond: Callable[[], Any], timeout_s: float, what: str, stack: Stack | None = None) -> Any:
    deadline = time.monotonic() + timeout_s
    while True:
        value = cond()
        if value:
            return value
        tail = f"\n{stack.output()}" if stack is not None else ""
        assert time.monotonic() < deadline, f"{what} not after {timeout_s} s{tail}"
        time.sleep(0.05)


def alive(pid: int) -> bool:
    try:
        return psutil.Process(pid).status() != psutil.STATUS_ZOMBIE
    except psutil.NoSuchProcess:
        return False


def start_stack(tmp_path: Path, *args: str, rtf: str = "8") -> Stack:
    """sim_control at a bounded real-time factor: these tests steer the car with a command per odometry sample,
    and a zero-stamped command expires after cmd_vel_timeout (0.5 s) of sim time. At rtf 0 on a fast machine
    that is ~15 ms of wall time, which this test process (decoding every topic) cannot promise on two cores."""
    stack = Stack("sim_control", tmp_path, *args, rtf=rtf)
    stack.connect()
    stack.watch_odom(ODOM)
    stack.wait_controllers_active(CONTROLLERS)
    stack.descendants()
    return stack


def drive(stack: Stack, vx: float, wz: float, index: int, value: float) -> None:
    """Command (vx, wz) on every odometry sample until odometry reports `value` at `index` (3: vx, 4: wz)."""
    stack.command(CMD, TWIST_STAMPED, {"twist": {"linear": {"x": vx}, "angular": {"z": wz}}})
    w = stack.watch
    deadline = stack.clock_ns + 20 * SEC
    while True:
        last = w.last(w.odom)
        if last is not None and abs(last.value[index] - value) <= 0.01:
            return
        assert stack.clock_ns < deadline, f"odometry never reached {value} (last: {last})\n{stack.output()}"
        stack.wait_sim(stack.clock_ns + SEC // 50)


def truth_at(stack: Stack, t_ns: int) -> tuple[float, float, float]:
    return stack.watch.at(stack.watch.truth, t_ns).value


def moved_m(a: tuple[float, ...], b: tuple[float, ...]) -> float:
    return math.hypot(b[0] - a[0], b[1] - a[1])
