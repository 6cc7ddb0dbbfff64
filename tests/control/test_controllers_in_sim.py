"""ros2_controllers' controllers hosted by the simulator's controller manager (gz_ros2_control) on real PyBullet
robots, over a real router: each robot is commanded as a user would (an action goal, a TwistStamped on the
controller's topic) and its motion is checked against the kinematics the controller's own odometry and
trajectory implement.
"""

from __future__ import annotations

import threading
import time
from pathlib import Path
from typing import Any

import pytest

from diffctl.description.robot_files import parse_description
from diffctl.description.sdf_loader import load_world

pytestmark = pytest.mark.slow

REPO = Path(__file__).resolve().parents[2]
EMPTY_WORLD = REPO / "config" / "worlds" / "empty.world"


def _box_link(name: str, size: tuple[float, float, float], mass: float, xyz: str = "0 0 0") -> str:
    sx, sy, sz = size
    i = mass * (sx * sx + sy * sy + sz * sz) / 12.0
    return (f'<link name="{name}"><inertial><origin xyz="{xyz}"/><mass value="{mass}"/>'
            f'<inertia ixx="{i}" iyy="{i}" izz="{i}" ixy="0" ixz="0" iyz="0"/></inertial>'
            f'<collision><origin xyz="{xyz}"/><geometry><box size="{sx} {sy} {sz}"/></geometry></collision>'
            f'<visual><origin xyz="{xyz}"/><geometry><box size="{sx} {sy} {sz}"/></geometry></visual></link>')


def _gz_plugin(params_file: Path) -> str:
    return ('<gazebo><plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin">'
            f"<parameters>{params_file}</parameters></plugin></gazebo>")


def rrbot_urdf(params_file: Path) -> str:
    """ros2_control_demos' rrbot: a two-link arm on a fixed post, position commands, position + velocity
    states, hanging in gravity as the original does."""
    joints = "".join(
        f'<joint name="{j}"><command_interface name="position"/><state_interface name="position"/>'
        f'<state_interface name="velocity"/></joint>' for j in ("joint1", "joint2"))
    return f"""<robot name="rrbot"><link name="world"/>
{_box_link("base_link", (0.1, 0.1, 2.0), 1.0, "0 0 1.0")}
{_box_link("link1", (0.1, 0.1, 1.0), 1.0, "0 0 0.45")}
{_box_link("link2", (0.1, 0.1, 1.0), 1.0, "0 0 0.45")}
<joint name="fixed" type="fixed"><parent link="world"/><child link="base_link"/></joint>
<joint name="joint1" type="continuous"><parent link="base_link"/><child link="link1"/>
<origin xyz="0 0.1 1.95"/><axis xyz="0 1 0"/><dynamics damping="0.7"/></joint>
<joint name="joint2" type="continuous"><parent link="link1"/><child link="link2"/>
<origin xyz="0 0.1 0.9"/><axis xyz="0 1 0"/><dynamics damping="0.7"/></joint>
<ros2_control name="RRBot" type="system"><hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
{joints}</ros2_control>{_gz_plugin(params_file)}</robot>"""


class Hosted:
    """A simulation on the test's router with one robot spawned; its manager is stepped on this thread."""

    def __init__(self, urdf: str) -> None:
        from diffctl.bus import open_session
        from diffctl.sim.runner import Simulation

        self.session = open_session()
        self.sim = Simulation(load_world(EMPTY_WORLD), rtf=0, paused=True, session=self.session)
        self.sim.spawn(parse_description(urdf, source="robot_description", name="robot"), urdf)
        self.rt = self.sim.models["robot"]
        assert self.rt.control is not None
        self.cm = self.rt.control.cm

    def step(self, n: int) -> None:
        st = self.sim.stepper
        st.drain()
        for _ in range(n):
            for h in st.step_hooks:
                h()
            self.sim.physics.step()
            st.sim_time_ns += st.step_ns
            st.run_due()

    @property
    def sim_time_s(self) -> float:
        return self.sim.stepper.sim_time_ns * 1e-9

    def run_until(self, pred: Any, what: str, timeout_s: float = 60.0, chunk: int = 10) -> None:
        deadline = time.monotonic() + timeout_s
        while not pred():
            assert time.monotonic() < deadline, f"timed out waiting for {what}"
            self.step(chunk)

    def activate(self, *names: str) -> None:
        for name in names:
            self.cm.load_controller(name)
            self.cm.configure_controller(name)
        result: list[tuple[bool, str]] = []
        t = threading.Thread(target=lambda: result.append(self.cm.switch_controller(list(names), [], timeout_s=30.0)))
        t.start()
        self.run_until(lambda: bool(result), "the switch")
        t.join()
        assert result[0][0], result

    def joint_positions(self, names: list[str]) -> list[float]:
        entity = self.rt.entity
        return [s[0] for s in entity.joint_states([entity.joint(n) for n in names])]

    def close(self) -> None:
        self.sim.close()


class ClientNode:
    """An rclpy-API node of the test with its own executor thread."""

    def __init__(self, name: str) -> None:
        from diffctl.client.executors import SingleThreadedExecutor
        from diffctl.client.node import Node

        self.node = Node(name)
        self.executor = SingleThreadedExecutor()
        self.executor.add_node(self.node)
        self._thread = threading.Thread(target=self.executor.spin, daemon=True)
        self._thread.start()

    def close(self) -> None:
        self.executor.shutdown(timeout_sec=2.0)
        self.node.destroy_node()


JTC_YAML = """controller_manager:
  ros__parameters:
    update_rate: 100
    joint_trajectory_controller:
      type: joint_trajectory_controller/JointTrajectoryController
joint_trajectory_controller:
  ros__parameters:
    joints: [joint1, joint2]
    command_interfaces: [position]
    state_interfaces: [position, velocity]
    action_monitor_rate: 20.0
    constraints:
      stopped_velocity_tolerance: 0.05
      goal_time: 1.0
      joint1: {trajectory: 0.2, goal: 0.02}
      joint2: {trajectory: 0.2, goal: 0.02}
"""


def test_joint_trajectory_controller_follows_a_goal_on_the_simulated_rrbot(router: str, tmp_path: Path) -> None:
    from diffctl.client.action.client import ActionClient
    from diffctl.client.interfaces import cls

    params = tmp_path / "rrbot_controllers.yaml"
    params.write_text(JTC_YAML)
    hosted = Hosted(rrbot_urdf(params))
    client = None
    try:
        hosted.activate("joint_trajectory_controller")
        hosted.step(200)  # holding the hanging arm where it was activated
        start = hosted.joint_positions(["joint1", "joint2"])
        assert start == pytest.approx([0.0, 0.0], abs=0.02)

        client = ClientNode("rrbot_goal_sender")
        action = cls("control_msgs/action/FollowJointTrajectory")
        sender = ActionClient(client.node, action, "/joint_trajectory_controller/follow_joint_trajectory")
        assert sender.wait_for_server(timeout_sec=10.0)
        states: list[Any] = []
        client.node.create_subscription(cls("control_msgs/msg/JointTrajectoryControllerState"),
                                        "/joint_trajectory_controller/controller_state", states.append, 100)
        goal = action.Goal()
        goal.trajectory.joint_names = ["joint2", "joint1"]  # another order than the controller's
        targets = {"joint1": 0.6, "joint2": -0.4}
        for k, t_s in ((1, 1.5), (2, 3.0)):
            point = cls("trajectory_msgs/msg/JointTrajectoryPoint")()
            point.positions = [targets["joint2"] * k / 2, targets["joint1"] * k / 2]
            point.time_from_start.sec, point.time_from_start.nanosec = int(t_s), int((t_s % 1) * 1e9)
            goal.trajectory.points.append(point)
        feedback: list[Any] = []
        sent = sender.send_goal_async(goal, feedback_callback=feedback.append)
        hosted.run_until(sent.done, "the goal's acceptance")
        handle = sent.result()
        assert handle.accepted
        t0 = handle.stamp.sec + handle.stamp.nanosec * 1e-9  # accepted at this sim time (the manager's clock)
        result = handle.get_result_async()
        hosted.run_until(result.done, "the goal's result")
        outcome = result.result()
        assert (outcome.result.error_code, outcome.result.error_string) == (0, "Goal successfully reached!")
        # The last feedback is the cycle that decided success: the trajectory's 3 s, then inside the goal
        # tolerance within goal_time (the result itself reaches the client at the 20 Hz monitor rate, wall time,
        # while the simulation runs unthrottled).
        stamp = feedback[-1].feedback.header.stamp
        assert 3.0 <= stamp.sec + stamp.nanosec * 1e-9 - t0 < 4.0
        final = hosted.joint_positions(["joint1", "joint2"])
        assert final == pytest.approx([0.6, -0.4], abs=0.02)
        assert feedback and list(feedback[-1].feedback.joint_names) == ["joint1", "joint2"]
        # Along the way the arm stayed inside the path tolerance of the reference the controller published,
        # and the reference is the trajectory's linear interpolation (positions only).
        moving = [s for s in states if 0.1 < s.reference.time_from_start.sec + s.reference.time_from_start.nanosec
                  * 1e-9 < 3.0]
        assert len(moving) > 100
        assert max(abs(e) for s in moving for e in s.error.positions) < 0.2
        mid = min(moving, key=lambda s: abs(s.reference.time_from_start.sec
                                            + s.reference.time_from_start.nanosec * 1e-9 - 2.25))
        assert list(mid.reference.positions) == pytest.approx([0.45, -0.3], abs=0.01)
    finally:
        if client is not None:
            client.close()
        hosted.close()
