"""ros2_controllers' controllers hosted by the simulator's controller manager (gz_ros2_control) on real PyBullet
robots, over a real router: each robot is commanded as a user would (an action goal, a TwistStamped on the
controller's topic) and its motion is checked against the kinematics the controller's own odometry and
trajectory implement: the rrbot follows a FollowJointTrajectory goal within its tolerances; an Ackermann car
(gz_ros2_control's ackermann_drivetrain demo in small) and a tricycle (its tricycle_drive demo) drive a commanded
arc, their steering joints at the angles of upstream's inverse kinematics and their published odometry on the true
pose; a mecanum robot drives sideways with upstream's wheel speeds.
"""

from __future__ import annotations

import itertools
import math
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

    def __init__(self, urdf: str, height_m: float = 0.0) -> None:
        from diffctl.bus import open_session
        from diffctl.description.pose import Pose
        from diffctl.sim.runner import Simulation

        self.session = open_session()
        self.sim = Simulation(load_world(EMPTY_WORLD), rtf=0, paused=True, session=self.session)
        pose = Pose.from_xyz_rpy((0.0, 0.0, height_m)) if height_m else None
        self.sim.spawn(parse_description(urdf, source="robot_description", name="robot", pose=pose), urdf)
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
                                        "/joint_trajectory_controller/controller_state", states.append, 100_000)
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
        # (the state queue is deep: the simulation runs unthrottled on this thread while the client's executor
        # takes the samples, 100 a sim second, and none of the goal's may be dropped)
        result = handle.get_result_async()
        hosted.run_until(result.done, "the goal's result")
        outcome = result.result()
        assert (outcome.result.error_code, outcome.result.error_string) == (0, "Goal successfully reached!")
        # Success is decided in the control loop: the trajectory's 3 s, then inside the goal tolerance within
        # goal_time. The controller then holds the last waypoint as a new one-point trajectory, so its published
        # reference time restarts: that cycle's stamp is the decision's (the result itself reaches the client at
        # the 20 Hz monitor rate, wall time, while the simulation runs unthrottled).
        def seconds(t: Any) -> float:
            return t.sec + t.nanosec * 1e-9

        def began(m: Any) -> float:  # when the trajectory a sample follows began
            return seconds(m.header.stamp) - seconds(m.reference.time_from_start)

        def goal_began() -> float | None:
            # The control loop takes the accepted trajectory at its next cycle; the simulation runs unthrottled on
            # this thread meanwhile, so on a loaded machine that can be a simulated second after the acceptance.
            starts = [began(m) for m in list(states) if began(m) >= t0 - 1e-3]
            return min(starts) if starts else None

        def decided_at() -> float | None:
            start = goal_began()
            if start is None:
                return None
            following = [m for m in list(states) if seconds(m.header.stamp) > start + 1.0]  # the goal's trajectory on
            for before, after in itertools.pairwise(following):
                if seconds(after.reference.time_from_start) < seconds(before.reference.time_from_start) - 1.0:
                    return seconds(after.header.stamp)
            return None

        hosted.run_until(lambda: decided_at() is not None, "the switch to holding the goal")
        assert 3.0 <= decided_at() - goal_began() < 4.0
        final = hosted.joint_positions(["joint1", "joint2"])
        assert final == pytest.approx([0.6, -0.4], abs=0.02)
        assert feedback and list(feedback[-1].feedback.joint_names) == ["joint1", "joint2"]
        # Along the way the arm stayed inside the path tolerance of the reference the controller published,
        # and the reference is the trajectory's linear interpolation (positions only). The goal's samples are
        # those of the trajectory begun after the acceptance (a sample's stamp less its reference time is when
        # its trajectory began) and before the switch to holding: the simulation also ran while the test waited
        # for the acceptance and for the result, the controller holding a one-point trajectory whose reference
        # time grows too (the arm where it was activated before, the goal after).
        decided = decided_at()
        goal = [s for s in states if seconds(s.header.stamp) - seconds(s.reference.time_from_start) >= t0 - 1e-3
                and seconds(s.header.stamp) < decided]
        moving = [s for s in goal if 0.1 < seconds(s.reference.time_from_start) < 3.0]
        assert len(moving) > 250  # 100 Hz for 3 s
        assert max(abs(e) for s in moving for e in s.error.positions) < 0.2
        second_leg = [s for s in moving if seconds(s.reference.time_from_start) >= 1.5]
        assert len(second_leg) > 100
        for s in second_leg:  # from (0.3, -0.2) at 1.5 s to (0.6, -0.4) at 3 s, joint1 and joint2 in that order
            k = (seconds(s.reference.time_from_start) - 1.5) / 1.5
            assert list(s.reference.positions) == pytest.approx([0.3 + 0.3 * k, -0.2 - 0.2 * k], abs=1e-3), k
    finally:
        if client is not None:
            client.close()
        hosted.close()


# --- car-like and mecanum robots (gz_ros2_control demos' layout: base_link at the rear axle centre) -------------
WHEEL_R = 0.15
WHEELBASE = 0.8
TRACK = 0.6


def _wheel(name: str, mass: float = 1.0) -> str:
    i = 0.4 * mass * WHEEL_R * WHEEL_R
    return (f'<link name="{name}"><inertial><mass value="{mass}"/><inertia ixx="{i}" iyy="{i}" izz="{i}" ixy="0" '
            f'ixz="0" iyz="0"/></inertial><collision><geometry><sphere radius="{WHEEL_R}"/></geometry></collision>'
            f'<visual><origin rpy="1.5708 0 0"/><geometry><cylinder radius="{WHEEL_R}" length="0.06"/></geometry>'
            "</visual></link>")


def _joint(name: str, kind: str, parent: str, child: str, xyz: str, axis: str) -> str:
    return (f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f'<origin xyz="{xyz}"/><axis xyz="{axis}"/></joint>')


def _knuckle(name: str) -> str:
    return (f'<link name="{name}"><inertial><mass value="0.2"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" '
            'ixz="0" iyz="0"/></inertial></link>')


def _control(joints: dict[str, tuple[str, ...]], params_file: Path) -> str:
    """A ros2_control block (joint → command interface, then its state interfaces) and the gz plugin."""
    body = "".join(f'<joint name="{j}"><command_interface name="{ifs[0]}"/>'
                   + "".join(f'<state_interface name="{s}"/>' for s in ifs[1:]) + "</joint>"
                   for j, ifs in joints.items())
    return (f'<ros2_control name="GazeboSystem" type="system"><hardware><plugin>gz_ros2_control/GazeboSimSystem'
            f"</plugin></hardware>{body}</ros2_control>{_gz_plugin(params_file)}")


def _chassis(mass: float = 10.0) -> str:
    return _box_link("base_link", (WHEELBASE + 0.4, TRACK - 0.1, 0.15), mass, f"{WHEELBASE / 2} 0 0.1")


def ackermann_urdf(params_file: Path) -> str:
    """gz_ros2_control's ackermann_drivetrain demo in small: driven rear wheels, two steered front wheels."""
    h = TRACK / 2
    parts = [_chassis(), _wheel("rear_left_wheel"), _wheel("rear_right_wheel"), _knuckle("left_knuckle"),
             _knuckle("right_knuckle"), _wheel("front_left_wheel"), _wheel("front_right_wheel"),
             _joint("rear_left_wheel_joint", "continuous", "base_link", "rear_left_wheel", f"0 {h} 0", "0 1 0"),
             _joint("rear_right_wheel_joint", "continuous", "base_link", "rear_right_wheel", f"0 {-h} 0", "0 1 0"),
             _joint("front_left_steering_joint", "revolute", "base_link", "left_knuckle", f"{WHEELBASE} {h} 0",
                    "0 0 1").replace("</joint>", '<limit lower="-0.8" upper="0.8" effort="100" velocity="5"/></joint>'),
             _joint("front_right_steering_joint", "revolute", "base_link", "right_knuckle", f"{WHEELBASE} {-h} 0",
                    "0 0 1").replace("</joint>", '<limit lower="-0.8" upper="0.8" effort="100" velocity="5"/></joint>'),
             _joint("front_left_wheel_joint", "continuous", "left_knuckle", "front_left_wheel", "0 0 0", "0 1 0"),
             _joint("front_right_wheel_joint", "continuous", "right_knuckle", "front_right_wheel", "0 0 0", "0 1 0")]
    traction = ("velocity", "velocity", "position")
    control = _control({"rear_left_wheel_joint": traction, "rear_right_wheel_joint": traction,
                        "front_left_steering_joint": ("position", "position"),
                        "front_right_steering_joint": ("position", "position")}, params_file)
    return f'<robot name="ackermann_drive">{"".join(parts)}{control}</robot>'


def tricycle_urdf(params_file: Path) -> str:
    """gz_ros2_control's tricycle_drive demo in small: a driven, steered front wheel, free rear wheels."""
    h = TRACK / 2
    parts = [_chassis(), _wheel("left_wheel"), _wheel("right_wheel"), _knuckle("steering_link"),
             _wheel("wheel_front_link", 2.0),
             _joint("left_wheel_joint", "continuous", "base_link", "left_wheel", f"0 {h} 0", "0 1 0"),
             _joint("right_wheel_joint", "continuous", "base_link", "right_wheel", f"0 {-h} 0", "0 1 0"),
             _joint("steering_joint", "revolute", "base_link", "steering_link", f"{WHEELBASE} 0 0", "0 0 1")
             .replace("</joint>", '<limit lower="-1.5" upper="1.5" effort="100" velocity="5"/></joint>'),
             _joint("traction_joint", "continuous", "steering_link", "wheel_front_link", "0 0 0", "0 1 0")]
    control = _control({"steering_joint": ("position", "position"),
                        "traction_joint": ("velocity", "velocity", "position")}, params_file)
    return f'<robot name="tricycle_drive">{"".join(parts)}{control}</robot>'


def mecanum_sdf(params_file: Path, wheel_speed_bound: float | None = None) -> str:
    """Four mecanum wheels as Gazebo models them (a contact with friction direction fdir1 and mu2 0) around the
    centre, base_link being the centre; `wheel_speed_bound` gives the wheels' velocity command interfaces that
    min/max (rad/s)."""
    hx, hy = WHEELBASE / 2, TRACK / 2
    links = ["<link name='base_link'><pose>0 0 0.25 0 0 0</pose><inertial><mass>10</mass><inertia><ixx>0.3</ixx>"
             "<iyy>0.3</iyy><izz>0.3</izz></inertia></inertial><collision name='c'><geometry><box><size>0.9 0.45 0.1"
             "</size></box></geometry></collision></link>"]
    joints = []
    for wheel, x, y, fdir in (("front_left", hx, hy, "1 -1 0"), ("front_right", hx, -hy, "1 1 0"),
                              ("rear_left", -hx, hy, "1 1 0"), ("rear_right", -hx, -hy, "1 -1 0")):
        links.append(
            f"<link name='{wheel}'><pose>{x} {y} {WHEEL_R} -1.5707963 0 0</pose><inertial><mass>0.5</mass>"
            "<inertia><ixx>0.003</ixx><iyy>0.003</iyy><izz>0.003</izz></inertia></inertial><collision name='c'>"
            f"<geometry><sphere><radius>{WHEEL_R}</radius></sphere></geometry><surface><friction><ode><mu>1.0</mu>"
            f"<mu2>0.0</mu2><fdir1 gz:expressed_in='base_link'>{fdir}</fdir1></ode></friction></surface></collision>"
            "</link>")
        joints.append(f"<joint name='{wheel}_joint' type='revolute'><parent>base_link</parent><child>{wheel}</child>"
                      "<axis><xyz expressed_in='__model__'>0 1 0</xyz></axis></joint>")
    bounds = "" if wheel_speed_bound is None else (
        f'<param name="min">{-wheel_speed_bound}</param><param name="max">{wheel_speed_bound}</param>')
    body = "".join(f'<joint name="{w}_joint"><command_interface name="velocity">{bounds}</command_interface>'
                   '<state_interface name="velocity"/><state_interface name="position"/></joint>'
                   for w in ("front_left", "front_right", "rear_left", "rear_right"))
    control = (f'<ros2_control name="GazeboSystem" type="system"><hardware><plugin>gz_ros2_control/GazeboSimSystem'
               f'</plugin></hardware>{body}</ros2_control><plugin filename="gz_ros2_control-system" '
               f'name="gz_ros2_control::GazeboSimROS2ControlPlugin"><parameters>{params_file}</parameters></plugin>')
    return (f"<?xml version='1.0'?><sdf version='1.9' xmlns:gz='http://gazebosim.org/schema'><model name='mecanum'>"
            f"{''.join(links)}{''.join(joints)}{control}</model></sdf>")


class Taken:
    """How many messages a hosted controller's subscription on `topic` has taken (its callback wrapped): the
    world is stepped on only once the controller has the command just sent, whatever the machine's load."""

    def __init__(self, hosted: Hosted, topic: str) -> None:
        node = hosted.cm.controllers[topic.split("/")[1]].instance.get_node()
        sub = next(s for s in node.subscriptions if s.topic_name == topic)
        self.count = 0
        self._changed = threading.Condition()
        inner = sub.callback

        def counting(msg: Any) -> None:
            inner(msg)
            with self._changed:
                self.count += 1
                self._changed.notify_all()

        sub.callback = counting

    def wait_past(self, count: int, timeout_s: float = 30.0) -> None:
        with self._changed:
            assert self._changed.wait_for(lambda: self.count > count, timeout_s), "the controller took no command"


def drive(hosted: Hosted, client: ClientNode, topic: str, twist: dict, seconds: float,
          samples: list[tuple[float, Any]] | None = None) -> None:
    """Publish a TwistStamped (stamp 0: "now") every 50 ms of sim time for `seconds`, each taken by the controller
    before the world steps on; record (sim time, true pose) every 50 ms."""
    from diffctl.client.interfaces import cls

    endpoints = client.__dict__.setdefault("_drive", {})
    if topic not in endpoints:
        pub = client.node.create_publisher(cls("geometry_msgs/msg/TwistStamped"), topic, 10)
        wait_until(lambda: pub.get_subscription_count() > 0, f"the controller's subscription to {topic}")
        endpoints[topic] = (pub, Taken(hosted, topic))
    pub, taken = endpoints[topic]
    msg = cls("geometry_msgs/msg/TwistStamped")()
    msg.twist.linear.x = twist.get("x", 0.0)
    msg.twist.linear.y = twist.get("y", 0.0)
    msg.twist.angular.z = twist.get("z", 0.0)
    end = hosted.sim_time_s + seconds
    while hosted.sim_time_s < end:
        before = taken.count
        pub.publish(msg)
        taken.wait_past(before)
        hosted.step(50)
        if samples is not None:
            samples.append((hosted.sim_time_s, hosted.rt.entity.pose()))


def motion(samples: list[tuple[float, Any]]) -> tuple[float, float, float]:
    """Mean (forward m/s, sideways m/s, yaw rad/s) in the body frame over the samples (the chord of each 50 ms
    step, turned half its heading change)."""
    from diffctl.description.pose import rpy_from_quat

    fwd = side = turn = 0.0
    for (_, p0), (_, p1) in itertools.pairwise(samples):
        y0, y1 = rpy_from_quat(p0.quat)[2], rpy_from_quat(p1.quat)[2]
        dyaw = math.remainder(y1 - y0, 2 * math.pi)
        heading = y0 + dyaw / 2
        dx, dy = p1.xyz[0] - p0.xyz[0], p1.xyz[1] - p0.xyz[1]
        fwd += math.cos(heading) * dx + math.sin(heading) * dy
        side += -math.sin(heading) * dx + math.cos(heading) * dy
        turn += dyaw
    span = samples[-1][0] - samples[0][0]
    return fwd / span, side / span, turn / span


def planar(pose: Any) -> tuple[float, float, float]:
    from diffctl.description.pose import rpy_from_quat

    return pose.xyz[0], pose.xyz[1], rpy_from_quat(pose.quat)[2]


def odometry_of(msgs: list[Any]) -> tuple[float, float, float]:
    p = msgs[-1].pose.pose
    return p.position.x, p.position.y, 2 * math.atan2(p.orientation.z, p.orientation.w)


def last_cycle_odometry(hosted: Hosted, msgs: list[Any]) -> tuple[float, float, float]:
    """The odometry the controller published at the world's last control cycle (10 ms at 100 Hz), once it has
    come: an earlier sample lags the true pose by as far as the robot went since."""
    last_cycle_ns = hosted.sim.stepper.sim_time_ns - 10_000_000

    def stamp_ns(m: Any) -> int:
        return m.header.stamp.sec * 1_000_000_000 + m.header.stamp.nanosec

    wait_until(lambda: msgs and stamp_ns(msgs[-1]) >= last_cycle_ns, "the last control cycle's odometry", 30.0)
    return odometry_of(msgs)


@pytest.mark.parametrize("enforce", [False, True])
def test_mecanum_wheel_commands_past_the_interfaces_max_pass_unless_enforce_command_limits(
        router: str, tmp_path: Path, enforce: bool) -> None:
    """A held-out mecanum robot's wheel interfaces have min/max ±1 rad/s: in Jazzy (enforce_command_limits false,
    gz_system.cpp clamping nothing) it drives at its command; with the flag on, the resource manager clamps each
    wheel to 1 rad/s and it drives at a third of it."""
    params = tmp_path / "mecanum.yaml"
    flag = f"    enforce_command_limits: {str(enforce).lower()}\n"
    params.write_text(MECANUM_YAML.replace("    update_rate: 100\n", "    update_rate: 100\n" + flag, 1))
    bound = 1.0
    hosted = Hosted(mecanum_sdf(params, wheel_speed_bound=bound))
    client = None
    try:
        hosted.activate("mecanum_drive_controller")
        client = ClientNode("mecanum_limits_driver")
        hosted.step(100)
        vy = 3 * bound * WHEEL_R  # wheels at 3 rad/s
        drive(hosted, client, "/mecanum_drive_controller/reference", {"y": vy}, 1.0)
        samples: list[tuple[float, Any]] = []
        drive(hosted, client, "/mecanum_drive_controller/reference", {"y": vy}, 1.0, samples)
        wheel = vy / WHEEL_R if not enforce else bound
        speeds = [s[1] for s in hosted.rt.entity.joint_states(
            [hosted.rt.entity.joint(f"{w}_joint") for w in ("front_left", "front_right", "rear_right", "rear_left")])]
        assert speeds == pytest.approx([-wheel, wheel, -wheel, wheel], rel=0.02)
        assert motion(samples)[1] == pytest.approx(wheel * WHEEL_R, rel=0.03)
    finally:
        if client is not None:
            client.close()
        hosted.close()


ACKERMANN_YAML = """controller_manager:
  ros__parameters:
    update_rate: 100
    ackermann_steering_controller:
      type: ackermann_steering_controller/AckermannSteeringController
ackermann_steering_controller:
  ros__parameters:
    reference_timeout: 0.5
    traction_joints_names: [rear_right_wheel_joint, rear_left_wheel_joint]
    steering_joints_names: [front_right_steering_joint, front_left_steering_joint]
    wheelbase: 0.8
    traction_track_width: 0.6
    traction_wheels_radius: 0.15
"""


def test_ackermann_steering_controller_drives_the_commanded_arc(router: str, tmp_path: Path) -> None:
    from diffctl.client.interfaces import cls

    params = tmp_path / "ackermann.yaml"
    params.write_text(ACKERMANN_YAML)
    hosted = Hosted(ackermann_urdf(params), height_m=WHEEL_R + 0.01)
    client = None
    try:
        hosted.activate("ackermann_steering_controller")
        client = ClientNode("ackermann_driver")
        odom: list[Any] = []
        client.node.create_subscription(cls("nav_msgs/msg/Odometry"), "/ackermann_steering_controller/odometry",
                                        odom.append, 10)
        hosted.step(300)
        v, w = 0.5, 0.25  # a 2 m radius
        drive(hosted, client, "/ackermann_steering_controller/reference", {"x": v, "z": w}, 1.5)
        samples: list[tuple[float, Any]] = []
        drive(hosted, client, "/ackermann_steering_controller/reference", {"x": v, "z": w}, 4.0, samples)
        # steering_controllers_library's inverse kinematics: the middle wheel's angle, each side's own
        phi = math.atan(w * WHEELBASE / v)
        rise, run, spread = 2 * WHEELBASE * math.sin(phi), 2 * WHEELBASE * math.cos(phi), TRACK * math.sin(phi)
        right, left = math.atan2(rise, run + spread), math.atan2(rise, run - spread)
        steer = hosted.joint_positions(["front_right_steering_joint", "front_left_steering_joint"])
        assert steer == pytest.approx([right, left], abs=0.02)
        forward, sideways, turn = motion(samples)
        assert forward == pytest.approx(v, rel=0.01) and turn == pytest.approx(w, rel=0.02)
        assert abs(sideways) < 0.01
        # the controller's odometry (from the wheels and steering) follows the true pose of base_link
        x, y, yaw = planar(hosted.rt.entity.pose())
        ox, oy, oyaw = last_cycle_odometry(hosted, odom)
        travelled = v * (hosted.sim_time_s - 1.0)
        assert math.hypot(ox - x, oy - y) < 0.02 * travelled
        assert abs(math.remainder(oyaw - yaw, 2 * math.pi)) < 0.02
    finally:
        if client is not None:
            client.close()
        hosted.close()


def wait_until(pred: Any, what: str, timeout_s: float = 10.0) -> None:
    deadline = time.monotonic() + timeout_s
    while not pred():
        assert time.monotonic() < deadline, f"timed out waiting for {what}"
        time.sleep(0.01)


TRICYCLE_YAML = """controller_manager:
  ros__parameters:
    update_rate: 100
    tricycle_controller:
      type: tricycle_controller/TricycleController
tricycle_controller:
  ros__parameters:
    traction_joint_name: traction_joint
    steering_joint_name: steering_joint
    wheel_radius: 0.15
    wheelbase: 0.8
    odom_frame_id: odom
    base_frame_id: base_link
    enable_odom_tf: true
    cmd_vel_timeout: 500
    use_stamped_vel: true
    traction: {max_acceleration: 5.0, max_deceleration: 8.0}
    steering: {min_position: -1.57, max_position: 1.57, max_velocity: 1.0}
"""


def test_tricycle_controller_drives_the_commanded_arc(router: str, tmp_path: Path) -> None:
    from diffctl.client.interfaces import cls

    params = tmp_path / "tricycle.yaml"
    params.write_text(TRICYCLE_YAML)  # gz_ros2_control's tricycle demo file, its dimensions ours
    hosted = Hosted(tricycle_urdf(params), height_m=WHEEL_R + 0.01)
    client = None
    try:
        hosted.activate("tricycle_controller")
        client = ClientNode("tricycle_driver")
        odom: list[Any] = []
        client.node.create_subscription(cls("nav_msgs/msg/Odometry"), "/tricycle_controller/odom", odom.append, 10)
        hosted.step(300)
        v, w = 0.5, -0.25  # a 2 m radius, to the right
        drive(hosted, client, "/tricycle_controller/cmd_vel", {"x": v, "z": w}, 2.0)
        samples: list[tuple[float, Any]] = []
        drive(hosted, client, "/tricycle_controller/cmd_vel", {"x": v, "z": w}, 4.0, samples)
        # tricycle_controller's inverse kinematics: the wheel turned to atan(ω·L / v)
        alpha = math.atan(w * WHEELBASE / v)
        assert hosted.joint_positions(["steering_joint"])[0] == pytest.approx(alpha, abs=0.02)
        forward, sideways, turn = motion(samples)
        assert forward == pytest.approx(v, rel=0.01) and turn == pytest.approx(w, rel=0.02)
        assert abs(sideways) < 0.01
        x, y, yaw = planar(hosted.rt.entity.pose())
        ox, oy, oyaw = last_cycle_odometry(hosted, odom)
        assert math.hypot(ox - x, oy - y) < 0.02 * v * hosted.sim_time_s
        assert abs(math.remainder(oyaw - yaw, 2 * math.pi)) < 0.02
    finally:
        if client is not None:
            client.close()
        hosted.close()


MECANUM_YAML = """controller_manager:
  ros__parameters:
    update_rate: 100
    mecanum_drive_controller:
      type: mecanum_drive_controller/MecanumDriveController
mecanum_drive_controller:
  ros__parameters:
    reference_timeout: 0.5
    front_left_wheel_command_joint_name: front_left_joint
    front_right_wheel_command_joint_name: front_right_joint
    rear_right_wheel_command_joint_name: rear_right_joint
    rear_left_wheel_command_joint_name: rear_left_joint
    kinematics:
      base_frame_offset: {x: 0.0, y: 0.0, theta: 0.0}
      wheels_radius: 0.15
      sum_of_robot_center_projection_on_X_Y_axis: 0.7
    base_frame_id: base_link
    odom_frame_id: odom
"""


def test_mecanum_drive_controller_drives_sideways(router: str, tmp_path: Path) -> None:
    from diffctl.client.interfaces import cls

    params = tmp_path / "mecanum.yaml"
    params.write_text(MECANUM_YAML)
    hosted = Hosted(mecanum_sdf(params))
    client = None
    try:
        hosted.activate("mecanum_drive_controller")
        client = ClientNode("mecanum_driver")
        odom: list[Any] = []
        client.node.create_subscription(cls("nav_msgs/msg/Odometry"), "/mecanum_drive_controller/odometry",
                                        odom.append, 10)
        hosted.step(300)
        vy = 0.3
        drive(hosted, client, "/mecanum_drive_controller/reference", {"y": vy}, 1.0)
        samples: list[tuple[float, Any]] = []
        drive(hosted, client, "/mecanum_drive_controller/reference", {"y": vy}, 3.0, samples)
        forward, sideways, turn = motion(samples)
        assert sideways == pytest.approx(vy, rel=0.02) and abs(forward) < 0.01 and abs(turn) < 0.01
        # mecanum inverse kinematics: (−vy, vy, −vy, vy) / r on front left, front right, rear right, rear left
        speeds = [s[1] for s in hosted.rt.entity.joint_states(
            [hosted.rt.entity.joint(f"{w}_joint") for w in ("front_left", "front_right", "rear_right", "rear_left")])]
        assert speeds == pytest.approx([-vy / WHEEL_R, vy / WHEEL_R, -vy / WHEEL_R, vy / WHEEL_R], rel=0.02)
        x, y, yaw = planar(hosted.rt.entity.pose())
        ox, oy, oyaw = last_cycle_odometry(hosted, odom)
        assert math.hypot(ox - x, oy - y) < 0.03 * vy * hosted.sim_time_s
        assert abs(math.remainder(oyaw - yaw, 2 * math.pi)) < 0.02
    finally:
        if client is not None:
            client.close()
        hosted.close()
