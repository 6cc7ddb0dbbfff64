"""Programs written as the ROS 2 tutorials and examples write them run unmodified on diffctl's rclpy: a
talker and a listener (Ctrl-C ends both cleanly), add_two_ints, the executors demo, the parameters demo with
--ros-args (its parameter read and set from diffctl's own CLI, as from `ros2 param`)."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import threading
from pathlib import Path

from tests.conftest import Procs
from tests.waiting import wait_for

EXAMPLES = Path(__file__).parent / "examples" / "tutorials"


class Output:
    """A child's merged output, read on a thread so the child never blocks on a full pipe."""

    def __init__(self, p: subprocess.Popen) -> None:
        self.lines: list[str] = []
        self._t = threading.Thread(target=self._read, args=(p,), daemon=True)
        self._t.start()

    def _read(self, p: subprocess.Popen) -> None:
        for line in p.stdout:
            self.lines.append(line.rstrip("\n"))

    def has(self, text: str) -> bool:
        return any(text in line for line in self.lines)

    def text(self) -> str:
        return "\n".join(self.lines)


def _start(procs: Procs, name: str, *args: str) -> tuple[subprocess.Popen, Output]:
    p = procs.start([sys.executable, str(EXAMPLES / name), *args], env={**os.environ, "PYTHONUNBUFFERED": "1"})
    return p, Output(p)


def _heard_numbers(heard: Output) -> list[int]:
    return [int(m[1]) for line in list(heard.lines) if (m := re.search(r'I heard: "Hello World: (\d+)"', line))]


def test_talker_and_listener(router: str, procs: Procs) -> None:
    listener, heard = _start(procs, "minimal_subscriber.py")
    talker, said = _start(procs, "minimal_publisher.py")
    # Three in a row, whichever the first is: the talker's first messages go out before discovery ends, and a
    # volatile subscription joining late (a loaded machine) misses them, as with rclpy.
    assert wait_for(lambda: len(_heard_numbers(heard)) >= 3, 20), heard.text() + said.text()
    first, *rest = _heard_numbers(heard)[:3]
    assert rest == [first + 1, first + 2], heard.text()
    # diffctl's own tools see the rclpy talker as any ROS 2 node.
    echo = subprocess.run([sys.executable, "-m", "diffctl", "topic", "echo", "/topic", "--once", "--timeout", "10"],
                          capture_output=True, text=True, timeout=30)
    assert "data: 'Hello World: " in echo.stdout, echo.stdout + echo.stderr
    assert said.has('[INFO] [') and said.has('] [minimal_publisher]: Publishing: "Hello World: 0"')
    # Ctrl-C: the tutorials' except clauses end both quietly, exit status 0, no traceback.
    assert procs.stop(talker, signal.SIGINT) == 0
    assert procs.stop(listener, signal.SIGINT) == 0
    assert "Traceback" not in said.text() + heard.text()


def test_add_two_ints(router: str, procs: Procs) -> None:
    server, served = _start(procs, "add_two_ints_server.py")
    client = subprocess.run([sys.executable, str(EXAMPLES / "add_two_ints_client.py"), "2", "3"],
                            capture_output=True, text=True, timeout=30)
    assert client.returncode == 0, client.stderr
    assert "] [minimal_client_async]: Result of add_two_ints: for 2 + 3 = 5" in client.stderr
    assert wait_for(lambda: served.has("Incoming request"), 5)
    call = subprocess.run([sys.executable, "-m", "diffctl", "service", "call", "/add_two_ints",
                           "example_interfaces/srv/AddTwoInts", "{a: 40, b: 2}"], capture_output=True, text=True,
                          timeout=30)
    assert "sum: 42" in call.stdout, call.stdout + call.stderr
    # SIGTERM: the server's `except ExternalShutdownException` ends it normally.
    assert procs.stop(server, signal.SIGTERM) == 0, served.text()


def test_executors_demo(router: str) -> None:
    p = subprocess.run([sys.executable, str(EXAMPLES / "executors_demo.py")], capture_output=True, text=True,
                       timeout=30)
    assert p.returncode == 0, p.stderr
    line = next(ln for ln in p.stderr.splitlines() if "heartbeats" in ln)
    heard, beats = int(line.split("heard ")[1].split()[0]), int(line.split(", ")[1].split()[0])
    # Run one after the other, the slow callbacks (90 % of the time) would leave ~7 heartbeats.
    assert heard >= 5 and beats >= 30, line


def test_parameters_demo(router: str, procs: Procs) -> None:
    node, out = _start(procs, "parameters_demo.py", "--ros-args", "-p", "my_parameter:=earth")
    assert wait_for(lambda: out.has("Hello earth!"), 20), out.text()
    cli = [sys.executable, "-m", "diffctl", "param"]
    got = subprocess.run([*cli, "get", "/minimal_param_node", "my_parameter"], capture_output=True, text=True,
                         timeout=30)
    assert "earth" in got.stdout, got.stdout + got.stderr
    subprocess.run([*cli, "set", "/minimal_param_node", "my_parameter", "mars"], check=True, capture_output=True,
                   timeout=30)
    assert wait_for(lambda: out.has("Hello mars!"), 10), out.text()
    assert procs.stop(node, signal.SIGINT) == 0
