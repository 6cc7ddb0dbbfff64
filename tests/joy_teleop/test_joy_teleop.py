"""joy_teleop as a real process on a real router, with the commands of upstream's example configuration and
tests (joy_teleop_example.yaml's walk_button, test_debounce.py's simple_message): an axis mapping streams a
TwistStamped while its deadman button is held, a fixed message goes once per press."""

from __future__ import annotations

import threading
import time
from pathlib import Path
from typing import Any

import pytest

from tests.probe import Probe
from tests.waiting import wait_for

pytestmark = pytest.mark.slow

CONFIG = """joy_teleop:
  ros__parameters:
    walk_button:
      type: topic
      interface_type: geometry_msgs/msg/TwistStamped
      topic_name: cmd_vel
      deadman_buttons: [4]
      axis_mappings:
        twist-linear-x: {axis: 1, scale: 0.5, offset: -0.03}
        twist-angular-z: {axis: 0, scale: 0.5, offset: 0}
        twist-linear-y: {axis: 2, scale: 0.3, offset: 0}
        twist-linear-z: {button: 2, scale: 3.0}
        header-frame_id: {value: 'my_tf_frame'}
    simple_message:
      type: topic
      interface_type: std_msgs/msg/String
      topic_name: /simple_message_type
      deadman_buttons: [2]
      message_value:
        data: {value: 'button2'}
"""


def test_axis_mappings_stream_and_fixed_messages_debounce(router: str, procs, tmp_path: Path) -> None:
    (tmp_path / "joy_teleop.yaml").write_text(CONFIG)
    teleop = procs.diffctl("run", "joy_teleop", "joy_teleop", "--ros-args", "--params-file",
                           str(tmp_path / "joy_teleop.yaml"))
    node = Probe("joy_probe")
    got: dict[str, list[Any]] = {"twist": [], "string": []}
    lock = threading.Lock()

    def keep(key: str):
        def on(m: Any) -> None:
            with lock:
                got[key].append(m)
        return on

    try:
        node.create_subscription("/cmd_vel", "geometry_msgs/msg/TwistStamped", keep("twist"))
        node.create_subscription("/simple_message_type", "std_msgs/msg/String", keep("string"))
        joy = node.create_publisher("/joy", "sensor_msgs/msg/Joy")
        assert wait_for(lambda: joy.subscription_count > 0, timeout_s=60), (procs.stop(teleop), teleop.stdout.read())
        assert wait_for(lambda: bool(node.graph.publishers("/cmd_vel")), timeout_s=30)

        held = {"axes": [0.4, 0.8, -1.0], "buttons": [0, 0, 1, 0, 1]}  # deadman 4 and button 2 held
        for _ in range(10):
            joy.publish(held)
            time.sleep(0.05)
        assert wait_for(lambda: len(got["twist"]) >= 10, timeout_s=30), len(got["twist"])
        t = got["twist"][-1]
        assert t.twist.linear.x == pytest.approx(0.8 * 0.5 - 0.03)
        assert t.twist.angular.z == pytest.approx(0.4 * 0.5)
        assert t.twist.linear.y == pytest.approx(-1.0 * 0.3)
        assert t.twist.linear.z == pytest.approx(3.0)
        assert t.header.frame_id == "my_tf_frame"
        assert wait_for(lambda: len(got["string"]) >= 1, timeout_s=30)
        with lock:
            assert [m.data for m in got["string"]] == ["button2"]  # ten messages with button 2 held: one press

        released = {"axes": [0.4, 0.8, -1.0], "buttons": [0, 0, 0, 0, 0]}
        joy.publish(released)
        time.sleep(0.2)
        count = len(got["twist"])
        for _ in range(5):
            joy.publish(released)
            time.sleep(0.05)
        joy.publish(held)  # a second press
        assert wait_for(lambda: len(got["string"]) == 2 and len(got["twist"]) > count, timeout_s=30)
        time.sleep(0.3)
        assert len(got["twist"]) == count + 1  # no deadman, no twist; the press streams again
    finally:
        node.close()
    assert procs.stop(teleop) == 0
