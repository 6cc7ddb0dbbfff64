"""`diffctl robot-state-publisher` as a real process on a real router, seen from a ROS-style node."""

from __future__ import annotations

import math
import threading
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np
import yaml

from diffctl.description.pose import Pose
from diffctl.interfaces import types
from tests.probe import Probe
from tests.waiting import wait_for

REPO = Path(__file__).resolve().parents[2]
CAR = REPO / "description" / "my_diff_car.sdf"


def pose_of(tf) -> Pose:
    t, r = tf.transform.translation, tf.transform.rotation
    return Pose((t.x, t.y, t.z), (r.x, r.y, r.z, r.w))


def test_description_static_and_moving_tf(router: str, procs, tmp_path: Path) -> None:
    # Started as the launcher does: parameters in a ROS params file, the SDF text as a YAML string.
    params = tmp_path / "rsp.yaml"
    params.write_text(
        yaml.safe_dump(
            {
                "/**": {
                    "ros__parameters": {
                        "robot_description": CAR.read_text(),
                        "publish_frequency": 1000.0,
                        "frame_prefix": "car/",
                    }
                }
            }
        )
    )
    rsp = procs.diffctl("robot-state-publisher", "--ros-args", "--params-file", str(params))
    node = Probe("rsp_probe")
    assert wait_for(lambda: any(e.node == "robot_state_publisher" for e in node.graph.publishers("/tf_static"))), (
        procs.stop(rsp),
        rsp.stdout.read(),
    )
    time.sleep(0.3)  # let the publisher's latched sample settle before a *late* subscriber appears

    got: dict[str, list] = {"desc": [], "static": [], "tf": []}
    lock = threading.Lock()

    def keep(kind: str) -> Callable[[object], None]:
        def cb(msg: object) -> None:
            with lock:
                got[kind].append(msg)

        return cb

    node.create_subscription("/robot_description", "std_msgs/msg/String", keep("desc"), latched=True)
    node.create_subscription("/tf_static", "tf2_msgs/msg/TFMessage", keep("static"), latched=True)
    node.create_subscription("/tf", "tf2_msgs/msg/TFMessage", keep("tf"))
    assert wait_for(lambda: got["desc"] and got["static"])
    assert got["desc"][0].data == CAR.read_text()
    static = {tf.child_frame_id: tf for tf in got["static"][0].transforms}
    assert set(static) == {"car/base_link", "car/caster", "car/lidar_link", "car/imu_link", "car/camera_link"}
    assert static["car/base_link"].header.frame_id == "car/base_footprint"
    assert pose_of(static["car/base_link"]).is_close(Pose((0, 0, 0.04)))
    assert pose_of(static["car/caster"]).is_close(Pose((-0.18, 0, -0.02)))
    assert static["car/lidar_link"].header.frame_id == "car/base_link"

    joints = node.create_publisher("/joint_states", "sensor_msgs/msg/JointState")
    assert wait_for(lambda: joints.subscription_count > 0)
    stamp_ns = 12_345_000_000_123
    msg = types.new(
        "sensor_msgs/msg/JointState",
        {
            "header": {"stamp": {"sec": stamp_ns // 10**9, "nanosec": stamp_ns % 10**9}},
            "name": ["base_link_to_left_wheel", "base_link_to_right_wheel", "not_a_joint"],
            "position": [math.pi / 2, -1.0, 3.0],
            "velocity": [],
            "effort": [],
        },
    )
    assert wait_for(lambda: bool(got["tf"]), every=lambda: joints.publish(msg))
    (tf_msg,) = got["tf"][:1]
    moving = {tf.child_frame_id: tf for tf in tf_msg.transforms}
    assert set(moving) == {"car/left_wheel", "car/right_wheel"}
    left, right = moving["car/left_wheel"], moving["car/right_wheel"]
    assert left.header.frame_id == "car/base_link"
    assert types.time_ns(left.header.stamp) == stamp_ns
    # the wheel turns in place about +y: same centre, pitch = joint angle
    assert pose_of(left).is_close(Pose.from_xyz_rpy((0, 0.15, 0), (0, math.pi / 2, 0)))
    assert pose_of(right).is_close(Pose.from_xyz_rpy((0, -0.15, 0), (0, -1.0, 0)))
    assert np.allclose(pose_of(left).rotate((1, 0, 0)), (0, 0, -1), atol=1e-12)  # +y spin tips x down

    code = procs.stop(rsp)
    out = rsp.stdout.read()
    assert code == 0, out
    assert "model 'my_diff_car': root 'base_footprint', 5 fixed and 2 moving joints" in out


def test_bad_description_exits_2_without_touching_the_bus(router: str, procs, tmp_path: Path) -> None:
    bad = tmp_path / "bad.sdf"
    bad.write_text('<sdf version="1.8"><model name="m">\n<link name="a"><pose/></link></model></sdf>')
    p = procs.diffctl("robot-state-publisher", "--description", str(bad))
    assert p.wait(30) == 2
    out = p.stdout.read()
    assert "robot_description:2: model[m]/link[a]/pose: empty <pose/>" in out, out
    assert "Traceback" not in out
