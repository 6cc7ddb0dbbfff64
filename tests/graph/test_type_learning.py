"""Types a process was not built with: learnt from a publisher's `~/get_type_description` (REP-2016), so
`diffctl topic echo` decodes them as `ros2 topic echo` does with dynamic typesupport."""

from __future__ import annotations

import subprocess
import sys
import textwrap

from rosbags.typesys import get_types_from_msg

from diffctl.bag.msgdefs import register_schema
from diffctl.interfaces import types
from diffctl.interfaces.type_description import describe, ros2msg_text

MIXED = "diffctl_test_msgs/msg/Mixed"
MIXED_MSG = """string<=10 label
int32[<=5] small
float64[3] fixed
geometry_msgs/Point[] points
uint8 flag
"""


def test_a_description_turns_back_into_the_same_definitions() -> None:
    register_schema(MIXED, "ros2msg", MIXED_MSG, "test")
    for t in (MIXED, "nav_msgs/msg/Odometry", "sensor_msgs/msg/CameraInfo", "sensor_msgs/msg/JointState"):
        found = get_types_from_msg(ros2msg_text(describe(t)), t)
        store = types.store().fielddefs
        for name, (_consts, fields) in found.items():
            assert fields == store[name][1], name  # field for field, bounds and nesting included


def test_topic_echo_learns_a_type_it_does_not_know(router: str, procs) -> None:
    publisher = textwrap.dedent(f"""
        import time
        from diffctl.bag.msgdefs import register_schema
        from diffctl.client import component
        from diffctl.client.node import Node
        from diffctl.interfaces import types
        register_schema({MIXED!r}, "ros2msg", {MIXED_MSG!r}, "test")
        # a full node: its ~/get_type_description is where the echo learns the type
        node = component.start(lambda: Node("mixed_talker")).node
        pub = node.bus_node.create_publisher("/mixed", {MIXED!r})
        print("ready", flush=True)
        while True:
            pub.publish(types.new({MIXED!r}, {{"label": "hello", "small": [1, 2], "fixed": [0.5, 1.5, 2.5],
                                               "points": [{{"x": 3.0}}], "flag": 7}}))
            time.sleep(0.05)
    """)
    talker = procs.start([sys.executable, "-c", publisher])
    first = talker.stdout.readline().strip()
    assert first == "ready", first + talker.stdout.read()
    echo = subprocess.run([sys.executable, "-m", "diffctl", "topic", "echo", "/mixed", "--once", "--timeout", "20"],
                          capture_output=True, text=True, timeout=60)
    assert echo.returncode == 0, echo.stderr
    assert "label: hello" in echo.stdout and "flag: 7" in echo.stdout and "x: 3.0" in echo.stdout, echo.stdout
