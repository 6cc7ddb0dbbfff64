"""End to end: a user's workspace with a xacro URDF diff-drive robot, launched by its own `.launch.py`.

The workspace (copied to a throw-away folder) is a gz_ros2_control demo as people write them: the launch file
builds `robot_description` with `Command([PathJoinSubstitution([FindExecutable(name='xacro')]), ' ', …])`,
includes ros_gz_sim's `gz_sim.launch.py` with `gz_args: ' -r -v 4 empty.sdf'`, spawns with `create -topic
robot_description -name diff_drive -allow_renaming true` and chains the spawners; the URDF carries the
gz_ros2_control plugin in a `<gazebo>` tag with `<parameters>$(find diffbot_gz)/config/….yaml</parameters>`,
a massless root and a caster lumped by its fixed joint.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from tests.conftest import free_port
from tests.e2e.stack import Stack
from tests.waiting import wait_for

WORKSPACE = Path(__file__).resolve().parent / "data" / "diffbot_ws"
CONTROLLERS = ("joint_state_broadcaster", "diff_drive_base_controller")


@pytest.fixture
def stack(tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    from diffctl.bus.session import close_session

    ws = tmp_path / "ws"
    shutil.copytree(WORKSPACE, ws)
    monkeypatch.setenv("DIFFCTL_ROUTER", f"tcp/127.0.0.1:{free_port()}")  # the launch's own router, this port
    monkeypatch.setenv("DIFFCTL_WORKSPACE", str(ws))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    logs = tmp_path / "logs"
    logs.mkdir()
    s = Stack(str(ws / "src" / "diffbot_gz" / "launch" / "diffbot.launch.py"), logs, rtf="1")
    try:
        yield s
    finally:
        s.kill()
        close_session()


@pytest.mark.slow
def test_xacro_urdf_robot_drives_from_its_own_launch_file(stack: Stack, tmp_path: Path) -> None:
    node = stack.connect(timeout_s=120)
    stack.wait_controllers_active(CONTROLLERS, timeout_s=180)

    descriptions: list[str] = []
    statics: list[set[tuple[str, str]]] = []
    node.create_subscription(
        "/robot_description", "std_msgs/msg/String", lambda m: descriptions.append(m.data), latched=True
    )
    node.create_subscription(
        "/tf_static",
        "tf2_msgs/msg/TFMessage",
        lambda m: statics.append({(t.header.frame_id, t.child_frame_id) for t in m.transforms}),
        latched=True,
    )
    assert wait_for(lambda: bool(descriptions) and bool(statics), 30), stack.output()
    # xacro ran as a command and resolved $(find diffbot_gz) through the workspace
    text = descriptions[-1]
    assert '<robot name="diffbot">' in text and "<xacro:" not in text
    assert "/diffbot_gz/config/diffbot_controllers.yaml</parameters>" in text
    # robot_state_publisher publishes the URDF as written: the caster (lumped in the simulator) keeps its frame
    assert {("base_footprint", "chassis"), ("chassis", "caster")} <= statics[-1]

    stack.watch_odom("/diff_drive_base_controller/odom")
    assert wait_for(lambda: stack.watch.last(stack.watch.odom) is not None, 30), stack.output()
    start = stack.watch.last(stack.watch.odom)
    stack.command(
        "/diff_drive_base_controller/cmd_vel",
        "geometry_msgs/msg/TwistStamped",
        {"twist": {"linear": {"x": 0.3}, "angular": {"z": 0.0}}},
    )
    stack.wait_sim(start.t_ns + int(3e9), timeout_s=120)
    stack.command("/diff_drive_base_controller/cmd_vel", "geometry_msgs/msg/TwistStamped", None)
    end = stack.watch.last(stack.watch.odom)
    x0, y0 = start.value[0], start.value[1]
    x1, y1, _, vx, _ = end.value
    assert x1 - x0 > 0.4, f"moved {x1 - x0:.3f} m in 3 s at 0.3 m/s\n{stack.output()}"
    assert abs(y1 - y0) < 0.1
    assert vx == pytest.approx(0.3, abs=0.08)
    assert stack.stop() == 0
    assert stack.survivors() == []
