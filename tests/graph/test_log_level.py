"""`--ros-args --log-level LEVEL` and `--log-level NAME:=LEVEL` reach every kind of diffctl node, as rcl reads
them for any ROS node: each component below logs at INFO while it starts (its model, its bridges, what it waits
for, the visualizer's and Foxglove server's address, the bag's topics), and with the level raised it prints
nothing but its product (the controller manager, its controllers and the spawner are in
tests/control/test_declarations_live). One unchanged process shows the lines would be there."""

from __future__ import annotations

import re
import time
from pathlib import Path
from typing import Any

import pytest

from tests.probe import call, probe
from tests.waiting import wait_for

REPO = Path(__file__).resolve().parents[2]
CAR = str(REPO / "description" / "my_diff_car.sdf")
LINE = re.compile(r"^\[(DEBUG|INFO|WARN|ERROR|FATAL)\] \[\d+\.\d{9}\] \[([^\]]*)\]: ", re.M)
# (node name prefix, command line without the --ros-args tail, logger name for the NAME:=LEVEL form)
KINDS = [
    ("/robot_state_publisher", ["robot-state-publisher", "--description", CAR], "robot_state_publisher"),
    ("/joint_state_publisher", ["joint-state-publisher"], "joint_state_publisher"),
    ("/static_transform_publisher_", ["tf2", "static_transform_publisher", "--frame-id", "a", "--child-frame-id",
                                      "b"], None),
    ("/tf2_echo", ["tf2", "tf2_echo", "a", "b", "20"], "tf2_echo"),
    ("/ros_gz_bridge", ["bridge", "/clock@rosgraph_msgs/msg/Clock[gz.msgs.Clock"], "ros_gz_bridge"),
    ("/ros_gz_image", ["image-bridge", "/camera"], "ros_gz_image"),
    ("/talker", ["run", "demo_nodes_py", "talker"], "talker"),
    ("/rviz2", ["viz", "--port", "0"], "rviz2"),
    ("/foxglove_bridge", ["foxglove-bridge", "--port", "0"], "foxglove_bridge"),
]
# What a node prints as its product, not as log messages: the transforms tf2_echo writes to stdout, the
# visualizer's page address (it carries the page's token).
PRODUCT = {"/tf2_echo": re.compile(r"(?!\[(DEBUG|INFO|WARN|ERROR|FATAL)\] ).*"),
           "/rviz2": re.compile(r"diffctl viz: open http://\S+")}


def _up(p: Any, prefix: str) -> str | None:
    """The node's name once its executor answers its parameter services (its start-up lines are written)."""
    name = next((n for n in p.graph.nodes() if n.startswith(prefix)), None)
    if name is None:
        return None
    call(p, f"{name}/list_parameters", "rcl_interfaces/srv/ListParameters")
    return name


@pytest.mark.slow
def test_every_kind_of_node_honours_log_level(router: str, procs: Any, tmp_path: Path) -> None:
    from tests.bag.test_files import write_bag

    write_bag(tmp_path / "played", n=5)
    kinds = [*KINDS, ("/rosbag2_recorder", ["bag", "record", "-a", "-o", str(tmp_path / "recorded")],
                      "rosbag2_recorder"),
             ("/rosbag2_player", ["bag", "play", str(tmp_path / "played"), "--start-paused"], "rosbag2_player")]
    started = []
    for i, (prefix, argv, logger) in enumerate(kinds):
        # every other node by its logger's name, the rest by the default level
        level = f"{logger}:=fatal" if logger and i % 2 else "fatal"
        started.append((prefix, procs.diffctl(*argv, "--ros-args", "--log-level", level)))
    control = procs.diffctl("tf2", "static_transform_publisher", "--frame-id", "c", "--child-frame-id", "d")
    p = probe("log_level_probe")
    try:
        for prefix, proc in started:
            assert wait_for(lambda pre=prefix: _up(p, pre) is not None, 60), (procs.stop(proc), proc.stdout.read())
        time.sleep(0.3)  # tf2_echo's "waiting for transform" comes from its 20 Hz timer
    finally:
        p.close()
    outputs = {}
    for prefix, proc in started:
        assert procs.stop(proc) == 0
        outputs[prefix] = proc.stdout.read()
    assert procs.stop(control) == 0
    assert [m[0] for m in LINE.findall(control.stdout.read())] == ["INFO"]
    # nothing at all: a line printed past the logger (a console note) would not honour the level either
    nothing = re.compile("$^")
    printed = {prefix: [ln for ln in out.splitlines() if ln.strip() and not PRODUCT.get(prefix, nothing).fullmatch(ln)]
               for prefix, out in outputs.items()}
    assert printed == {prefix: [] for prefix, _ in started}
