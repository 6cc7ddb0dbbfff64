"""demo_nodes_cpp / demo_nodes_py nodes and the `ros2` command, as real processes on a real router."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import yaml

from tests.conftest import Procs
from tests.waiting import lines_until

HERE = Path(__file__).resolve().parent
LOG = r"\[INFO\] \[\d+\.\d+\] \[{node}\]: "


def _ros2(*args: str, env: dict[str, str] | None = None, timeout: float = 60) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-c", "from diffctl.cli.ros2 import main; main()", *args],
        capture_output=True, text=True, timeout=timeout, start_new_session=True, env=env,
    )


def _read_until(p: subprocess.Popen, pattern: str, timeout_s: float = 30) -> str:
    """Lines of `p` up to the first matching `pattern`; fails with what was seen after `timeout_s`."""
    seen, found = lines_until(p.stdout, lambda line: re.search(pattern, line) is not None, timeout_s)
    if found:
        return "".join(seen)
    raise AssertionError(f"{pattern!r} not in output:\n" + "".join(seen))


def test_cpp_talker_to_py_listener_and_cpp_service_pair(router: str, procs: Procs) -> None:
    talker = procs.diffctl("run", "demo_nodes_cpp", "talker")
    listener = procs.diffctl("run", "demo_nodes_py", "listener")
    _read_until(talker, LOG.format(node="talker") + re.escape("Publishing: 'Hello World: 1'"))
    _read_until(listener, LOG.format(node="listener") + r"I heard: \[Hello World: \d+\]")
    info = _ros2("topic", "info", "/chatter", "-v")
    assert info.returncode == 0, info.stderr
    publishers, subscriptions = info.stdout.split("Subscriptions:")
    assert "History (Depth): KEEP_LAST (7)" in publishers, info.stdout  # rclcpp::KeepLast{7}
    assert "History (Depth): KEEP_LAST (10)" in subscriptions, info.stdout
    assert procs.stop(talker) == 0 and procs.stop(listener) == 0

    server = procs.diffctl("run", "demo_nodes_cpp", "add_two_ints_server", "--ros-args", "-p", "one_shot:=true")
    client = procs.diffctl("run", "demo_nodes_cpp", "add_two_ints_client")
    out = _read_until(client, LOG.format(node="add_two_ints_client") + r"Result of add_two_ints: 5")
    assert client.wait(30) == 0, out
    request = _read_until(server, LOG.format(node="add_two_ints_server") + r"Incoming request")
    assert _read_until(server, r".").endswith("a: 2 b: 3\n"), request  # the line after it
    assert server.wait(30) == 0  # one_shot: the server stops after its first request, as upstream's


def test_ros2_command_maps_verbs_onto_diffctl(router: str, procs: Procs, tmp_path: Path) -> None:
    board = procs.diffctl("run", "demo_nodes_cpp", "parameter_blackboard", "--ros-args", "-p", "seed:=3")
    _read_until(board, LOG.format(node="parameter_blackboard")
                + re.escape("Parameter blackboard node named '/parameter_blackboard' ready, and serving '")
                + r"\d+' parameters already!")
    r = _ros2("param", "set", "/parameter_blackboard", "color", "blue")
    assert r.returncode == 0 and "Set parameter successful" in r.stdout, r.stdout + r.stderr
    r = _ros2("param", "get", "/parameter_blackboard", "color")
    assert r.returncode == 0 and "blue" in r.stdout, r.stdout + r.stderr
    r = _ros2("node", "list")
    assert "/parameter_blackboard" in r.stdout.split(), r.stdout
    procs.stop(board)

    r = _ros2("bags", "record")
    assert r.returncode == 2
    assert "ros2 verb 'bags' is not available without ROS 2 (did you mean 'bag'?)" in r.stderr
    assert "bag, control, interface, launch, lifecycle, node, param, pkg, run, service, topic" in r.stderr
    assert _ros2().returncode == 2 and _ros2("--help").returncode == 0

    # a real ros2 on PATH (a sourced ROS 2) takes over with the same arguments
    real = tmp_path / "opt" / "ros2"
    real.parent.mkdir()
    real.write_text("#!/bin/sh\necho real ros2 \"$@\"\n")
    real.chmod(0o755)
    env = {**os.environ, "PATH": f"{real.parent}{os.pathsep}{os.environ['PATH']}"}
    r = _ros2("topic", "list", env=env)
    assert r.stdout == "real ros2 topic list\n", r.stdout + r.stderr


def test_put_on_a_launchs_path_only_without_a_real_ros2(tmp_path: Path, monkeypatch) -> None:
    from diffctl.cli.ros2 import find_real_ros2, put_ros2_on_path

    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    env = {"PATH": "/usr/bin:/bin"}
    folder = put_ros2_on_path(env)
    assert folder is not None and env["PATH"].split(os.pathsep)[0] == str(folder)
    assert find_real_ros2(env["PATH"]) is None  # diffctl's own script is never taken for a real one
    opt = tmp_path / "opt"
    opt.mkdir()
    (opt / "ros2").write_text("#!/bin/sh\n")
    (opt / "ros2").chmod(0o755)
    env = {"PATH": f"/usr/bin{os.pathsep}{opt}"}
    assert put_ros2_on_path(env) is None and env["PATH"] == f"/usr/bin{os.pathsep}{opt}"


def test_record_rosbag_launch_test_runs_ros2_bag(tmp_path: Path) -> None:
    # as ros2/examples' record_rosbag_launch_test.py: demo_nodes_cpp talker + `ros2 bag record` in ExecuteProcess
    bag = tmp_path / "bag"
    env = {**os.environ, "BAG_DIR": str(bag)}
    env.pop("DIFFCTL_ROUTER", None)
    r = subprocess.run(
        [sys.executable, "-m", "diffctl", "test", str(HERE / "launch_tests" / "record_bag_launch_test.py")],
        capture_output=True, text=True, timeout=180, start_new_session=True, env=env, cwd=tmp_path,
    )
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    meta = yaml.safe_load((bag / "metadata.yaml").read_text())["rosbag2_bagfile_information"]
    counts = {t["topic_metadata"]["name"]: t["message_count"] for t in meta["topics_with_message_count"]}
    assert counts.get("/chatter", 0) >= 1, counts


def test_shutdown_inside_a_callback_ends_spin_as_in_rclpy(router: str) -> None:
    # demo_nodes_cpp's one_shot add_two_ints_server shuts down from its timer; rclpy's spin then returns
    code = (
        "import rclpy\n"
        "rclpy.init()\n"
        "node = rclpy.create_node('x')\n"
        "timer = node.create_timer(0.05, lambda: rclpy.shutdown())\n"
        "rclpy.spin(node)\n"
        "print('spin returned', flush=True)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=30)
    assert r.returncode == 0 and r.stdout == "spin returned\n", r.stdout + r.stderr


LIFECYCLE_NODE = """
import rclpy
from rclpy.lifecycle import LifecycleNode
rclpy.init()
node = LifecycleNode('lc')
print('up', flush=True)
try:
    rclpy.spin(node)
except KeyboardInterrupt:
    pass
"""


def test_ros2_lifecycle_verbs(router: str, procs: Procs) -> None:
    node = procs.start([sys.executable, "-c", LIFECYCLE_NODE])
    _read_until(node, "up")

    def lc(*args: str) -> subprocess.CompletedProcess[str]:
        return _ros2("lifecycle", *args)

    r = lc("nodes")
    assert "/lc" in r.stdout.split(), r.stdout + r.stderr
    assert lc("get", "/lc").stdout == "unconfigured [1]\n"
    r = lc("set", "/lc", "configure")
    assert (r.returncode, r.stdout) == (0, "Transitioning successful\n"), r.stderr
    assert lc("get", "lc").stdout == "inactive [2]\n"
    listed = lc("list", "/lc").stdout
    assert "- activate [3]\n\tStart: inactive\n\tGoal: activating\n" in listed, listed
    r = lc("set", "/lc", "jump")
    assert r.returncode == 1 and r.stderr.startswith("Unknown transition requested, available ones are:\n- "), r.stderr
    r = lc("get", "/nobody")
    assert r.returncode == 1 and r.stderr == "Node not found\n"


def test_cpp_set_and_get_parameters_prints_rclcpp_values(router: str) -> None:
    r = subprocess.run(
        [sys.executable, "-m", "diffctl", "run", "demo_nodes_cpp", "set_and_get_parameters"],
        capture_output=True, text=True, timeout=60, start_new_session=True,
    )
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    # rclcpp's Parameter::value_to_string: std::to_string for doubles, boolalpha and 0x-hex arrays
    assert re.search(
        LOG.format(node="set_and_get_parameters") + "\nParameter name: foo\nParameter value \\(integer\\): 2\n"
        "Parameter name: baz\nParameter value \\(double\\): 1.450000\n"
        "Parameter name: foobarbaz\nParameter value \\(bool_array\\): \\[true, false\\]\n"
        "Parameter name: toto\nParameter value \\(byte_array\\): \\[0xff, 0x7f\\]\n",
        out,
    ), out
