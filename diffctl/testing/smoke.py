"""`diffctl test --init PKG`: a launch test that proves PKG's robot comes up and drives, written as a user would.

What the test needs is read from the package once, here, and written into the file as named constants the
user can read and edit: the bringup launch file (the one that spawns the diff drive controller), the
controller's name and YAML, the left wheel's joint, and that wheel's radius in the robot's description (SDF or
URDF). The test brings the launch up, waits for the controller to be active, drives on its cmd_vel for
DRIVE_SIM_S seconds of simulated time, and checks odometry against the command and against how far the
wheels really turned (a wrong wheel_radius in the YAML shows there), then that everything exits cleanly.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import yaml
from lxml import etree

from diffctl.errors import ConfigError

DIFF_DRIVE_TYPE = "diff_drive_controller/DiffDriveController"
LAUNCH_SUFFIXES = (".launch.py", ".launch.yaml", ".launch.xml", ".yaml", ".xml")
QUIET_ARGUMENTS = {"viz": "false", "gui": "false", "rviz": "false", "use_rviz": "false", "record": "false",
                   "rtf": "4"}  # 4x real time: quick, and a command's latency costs little sim time


@dataclass(frozen=True)
class RobotFacts:
    package: str
    launch_file: str  # relative to the package's share directory
    controller: str
    controller_yaml: Path
    left_wheel: str
    cmd_vel_timeout_s: float
    wheel_radius_m: float | None
    wheel_radius_from: str
    launch_arguments: dict[str, str]


SKIP_DIRS = {"__pycache__", "node_modules", "build", "install", "log", "test-output", "tests", "test", "bench"}


def _files(share: Path, pattern: str, depth: int = 4) -> list[Path]:
    """Files under a share directory, hidden folders and build/test trees left out (a package's share may be
    its source folder, diffctl's demo package the repository itself)."""
    out: list[Path] = []

    def walk(folder: Path, level: int) -> None:
        try:
            entries = sorted(folder.iterdir())
        except OSError:
            return
        for entry in entries:
            if entry.is_dir():
                if level < depth and not entry.name.startswith(".") and entry.name not in SKIP_DIRS:
                    walk(entry, level + 1)
            elif entry.match(pattern):
                out.append(entry)

    walk(share, 0)
    return out


def _controller(share: Path) -> tuple[str, Path, str, float]:
    for path in _files(share, "*.yaml"):
        if "diff_drive_controller" not in path.read_text(errors="replace"):
            continue
        try:
            data = yaml.safe_load(path.read_text())
        except yaml.YAMLError:
            continue
        if not isinstance(data, dict):
            continue
        for name, body in data.items():
            params = (body or {}).get("ros__parameters", {}) if isinstance(body, dict) else {}
            if params.get("type") == DIFF_DRIVE_TYPE:
                wheels = params.get("left_wheel_names") or []
                if not wheels:
                    raise ConfigError(f"{path}: {name} has no left_wheel_names")
                return str(name), path, str(wheels[0]), float(params.get("cmd_vel_timeout", 0.5))
    raise ConfigError(f"no controller YAML with a {DIFF_DRIVE_TYPE} under {share}",
                      hint="the smoke test drives a diff drive robot")


def _launch_file(share: Path, controller_yaml: Path) -> Path:
    candidates = [p for p in sorted((share / "launch").glob("*")) if p.name.endswith(LAUNCH_SUFFIXES)] \
        if (share / "launch").is_dir() else []
    fitting = [p for p in candidates if controller_yaml.name in (t := p.read_text(errors="replace"))
               and "spawner" in t]

    def rank(p: Path) -> tuple[int, int, str]:
        # A simulated robot's bringup first (mock hardware does not roll wheels), Python files before others.
        text = p.read_text(errors="replace")
        return (0 if "gz_sim" in text else 1, 0 if p.name.endswith(".launch.py") else 1, p.name)

    if fitting:
        return sorted(fitting, key=rank)[0]
    raise ConfigError(
        f"no launch file under {share / 'launch'} spawns the controller of {controller_yaml.name}",
        hint="candidates: " + (", ".join(p.name for p in candidates) or "none"),
    )


def _radius_in(path: Path, joint: str) -> float | None:
    try:
        if path.name.endswith(".xacro"):
            import xacro

            root = etree.fromstring(xacro.process_file(str(path)).toxml().encode())
        else:
            root = etree.parse(str(path)).getroot()
    except Exception:
        return None
    for j in root.iter("joint"):
        if j.get("name") != joint:
            continue
        child = j.find("child")
        link_name = (child.get("link") if child is not None and child.get("link") else
                     (child.text or "").strip() if child is not None else "")
        for link in root.iter("link"):
            if link.get("name") != link_name:
                continue
            for cyl in link.iter("cylinder"):
                value = cyl.get("radius")
                if value is None and cyl.find("radius") is not None:
                    value = cyl.find("radius").text
                if value:
                    return float(value)
    return None


def _wheel_radius(shares: list[Path], joint: str) -> tuple[float | None, str]:
    for share in shares:
        for pattern in ("*.sdf", "*.urdf", "*.xacro"):
            for path in _files(share, pattern):
                if joint not in path.read_text(errors="replace"):
                    continue
                radius = _radius_in(path, joint)
                if radius is not None:
                    return radius, path.name
    return None, ""


def _declared_arguments(launch: Path) -> set[str]:
    """The names of the arguments the launch file declares (as `ros2 launch --show-args` reads them); none when
    it cannot be read without running it."""
    from diffctl.launch.launch_description_sources import AnyLaunchDescriptionSource

    try:
        description = AnyLaunchDescriptionSource(str(launch)).try_get_launch_description_without_context()
        return {a.name for a in description.get_launch_arguments()} if description is not None else set()
    except Exception:
        return set()


def robot_facts(package: str) -> RobotFacts:
    from diffctl.workspace import find_package

    share = find_package(package).share
    controller, controller_yaml, left_wheel, cmd_vel_timeout_s = _controller(share)
    launch = _launch_file(share, controller_yaml)
    text = launch.read_text(errors="replace")
    shares = [share]
    for name in re.findall(r"""["']([A-Za-z][A-Za-z0-9_]*)["']""", text):
        try:
            other = find_package(name).share
        except Exception:
            continue
        if other not in shares:
            shares.append(other)
    radius, radius_from = _wheel_radius(shares, left_wheel)
    declared = _declared_arguments(launch)
    arguments = {k: v for k, v in QUIET_ARGUMENTS.items() if k in declared}
    return RobotFacts(package, str(launch.relative_to(share)), controller, controller_yaml, left_wheel,
                      cmd_vel_timeout_s, radius, radius_from, arguments)


def render(facts: RobotFacts) -> str:
    radius = "None" if facts.wheel_radius_m is None else repr(facts.wheel_radius_m)
    source = "launch_description_sources.PythonLaunchDescriptionSource" if facts.launch_file.endswith(".py") \
        else "launch_description_sources.AnyLaunchDescriptionSource"
    return TEMPLATE.format(
        package=facts.package,
        launch_file=facts.launch_file,
        controller=facts.controller,
        controller_yaml=facts.controller_yaml.name,
        left_wheel=facts.left_wheel,
        cmd_vel_timeout=repr(facts.cmd_vel_timeout_s),
        radius=radius,
        radius_from=facts.wheel_radius_from or "not found in the description",
        arguments=repr(facts.launch_arguments),
        source=source,
    )


def write_smoke_test(package: str, workspace: Path | None, output: Path | None = None) -> Path:
    from diffctl.workspace import find_package

    facts = robot_facts(package)
    if output is None:
        found = find_package(package)
        base = found.source if found.source is not None else Path.cwd()
        output = base / "test" / f"test_{package}_smoke.launch.py"
    if output.exists():
        raise ConfigError(f"{output} exists already", hint="remove it, or pass -o FILE")
    output.parent.mkdir(parents=True, exist_ok=True)
    output.write_text(render(facts))
    return output


TEMPLATE = '''\
"""Smoke test of {package}'s robot (written by `diffctl test --init {package}`; edit it as you like).

Brings up LAUNCH_FILE, waits for the controllers to be active, drives DRIVE_SIM_S seconds of simulated time
at SPEED_M_S on CONTROLLER's cmd_vel, checks odometry against the command and against how far the wheels
turned, then that every process exits cleanly. Run it with `diffctl test`, `launch_test` or pytest.
"""

import os
import time
import unittest

import launch
import launch_testing
import launch_testing.actions
import launch_testing.asserts
import pytest
import rclpy
from ament_index_python.packages import get_package_share_directory
from controller_manager_msgs.msg import ControllerManagerActivity
from geometry_msgs.msg import TwistStamped
from launch import launch_description_sources
from nav_msgs.msg import Odometry
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState

PACKAGE = "{package}"
LAUNCH_FILE = "{launch_file}"
LAUNCH_ARGUMENTS = {arguments}
CONTROLLER_MANAGER = "/controller_manager"
CONTROLLER = "{controller}"  # from {controller_yaml}
CMD_VEL_TIMEOUT_S = {cmd_vel_timeout}  # the controller's cmd_vel_timeout
LEFT_WHEEL_JOINT = "{left_wheel}"
WHEEL_RADIUS_M = {radius}  # the wheel of the robot's description ({radius_from})
SPEED_M_S = 0.5
DRIVE_SIM_S = 2.0
TOLERANCE_M = 0.1
ACTIVE_TIMEOUT_S = 30.0


@pytest.mark.launch_test
def generate_test_description():
    bringup = launch.actions.IncludeLaunchDescription(
        {source}(
            os.path.join(get_package_share_directory(PACKAGE), LAUNCH_FILE)
        ),
        launch_arguments=LAUNCH_ARGUMENTS.items(),
    )
    return launch.LaunchDescription([bringup, launch_testing.actions.ReadyToTest()])


class TestDrive(unittest.TestCase):
    def setUp(self):
        rclpy.init()
        self.node = rclpy.create_node("smoke_test")
        self.latest = {{}}
        self.odometry = []  # every odometry message, to see when the command took effect
        for topic, msg_type in ((f"/{{CONTROLLER}}/odom", Odometry), ("/joint_states", JointState),
                                ("/clock", Clock)):
            self.node.create_subscription(msg_type, topic, lambda m, t=topic: self.on_message(t, m), 100)
        latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL,
                             reliability=ReliabilityPolicy.RELIABLE)
        self.node.create_subscription(ControllerManagerActivity, f"{{CONTROLLER_MANAGER}}/activity",
                                      lambda m: self.latest.__setitem__("activity", m), latched)

    def on_message(self, topic, msg):
        self.latest[topic] = msg
        if topic.endswith("/odom"):
            self.odometry.append(msg)

    def tearDown(self):
        self.node.destroy_node()
        rclpy.shutdown()

    def spin_until(self, condition, timeout_s, what):
        deadline = time.monotonic() + timeout_s
        while not condition():
            if time.monotonic() > deadline:
                self.fail(f"{{what}} within {{timeout_s:g}} s")
            rclpy.spin_once(self.node, timeout_sec=0.02)

    def sim_s(self):
        stamp = self.latest["/clock"].clock
        return stamp.sec + stamp.nanosec * 1e-9

    def controller_states(self):
        activity = self.latest.get("activity")
        return {{}} if activity is None else {{c.name: c.state.label for c in activity.controllers}}

    def all_active(self):
        states = self.controller_states()
        return CONTROLLER in states and all(label == "active" for label in states.values())

    def moving_since_s(self):
        """Sim time of the last odometry at rest before the robot moved: the command took effect right after."""
        at_rest = None
        for msg in self.odometry:
            if abs(msg.twist.twist.linear.x) > 1e-6:
                break
            at_rest = msg.header.stamp.sec + msg.header.stamp.nanosec * 1e-9
        return at_rest

    def wheel_rad(self):
        js = self.latest["/joint_states"]
        return js.position[list(js.name).index(LEFT_WHEEL_JOINT)]

    def test_drives_on_cmd_vel(self):
        deadline = time.monotonic() + ACTIVE_TIMEOUT_S
        while not self.all_active():
            if time.monotonic() > deadline:
                states = self.controller_states() or "none"
                self.fail(f"controllers not active within {{ACTIVE_TIMEOUT_S:g}} s: {{states}} "
                          f"(from {{CONTROLLER_MANAGER}}/activity)")
            rclpy.spin_once(self.node, timeout_sec=0.02)
        odom = f"/{{CONTROLLER}}/odom"
        self.spin_until(lambda: all(t in self.latest for t in (odom, "/joint_states", "/clock")), 10.0,
                        "no odometry, joint states or clock")
        if LEFT_WHEEL_JOINT not in self.latest["/joint_states"].name:
            names = list(self.latest["/joint_states"].name)
            self.fail(f"joint {{LEFT_WHEEL_JOINT}} is not in /joint_states: {{names}}")
        pub = self.node.create_publisher(TwistStamped, f"/{{CONTROLLER}}/cmd_vel", 10)
        self.spin_until(lambda: pub.get_subscription_count() > 0, 10.0, f"nothing subscribes {{CONTROLLER}}/cmd_vel")
        x0, wheel0, t0 = self.latest[odom].pose.pose.position.x, self.wheel_rad(), self.sim_s()
        # Stamped so that the controller's own clock ends the drive at t0 + DRIVE_SIM_S (each command is good
        # for CMD_VEL_TIMEOUT_S after its stamp), however late this process gets to publish on a busy machine.
        until = t0 + DRIVE_SIM_S - CMD_VEL_TIMEOUT_S
        command = TwistStamped()
        command.header.stamp.sec = int(until)
        command.header.stamp.nanosec = int((until - int(until)) * 1e9)
        command.twist.linear.x = SPEED_M_S
        while self.sim_s() - t0 < DRIVE_SIM_S:
            pub.publish(command)
            end = time.monotonic() + 0.02
            while time.monotonic() < end:
                rclpy.spin_once(self.node, timeout_sec=0.005)
        pub.publish(TwistStamped())  # stop, and let the controller ramp down
        self.spin_until(lambda: abs(self.latest[odom].twist.twist.linear.x) < 1e-3, 10.0, "the robot did not stop")
        travelled = self.latest[odom].pose.pose.position.x - x0
        # From the controller's first update with the command to the command's end (the ramps up and down, at
        # the same acceleration, cancel out): independent of how late this process published.
        driven_s = t0 + DRIVE_SIM_S - (self.moving_since_s() or t0)
        expected = SPEED_M_S * driven_s
        rolled = None if WHEEL_RADIUS_M is None else (self.wheel_rad() - wheel0) * WHEEL_RADIUS_M
        print(f"odometry: {{travelled:.3f}} m, wheels: {{rolled if rolled is None else round(rolled, 3)}} m, "
              f"commanded: {{expected:.3f}} m", flush=True)
        self.assertAlmostEqual(
            travelled, expected, delta=TOLERANCE_M,
            msg=f"odometry says the robot drove {{travelled:.3f}} m; {{SPEED_M_S}} m/s for the {{driven_s:.2f}} s "
                f"of sim time the command was in effect is {{expected:.3f}} m",
        )
        if rolled is not None:
            self.assertAlmostEqual(
                rolled, travelled, delta=TOLERANCE_M,
                msg=f"the wheels rolled {{rolled:.3f}} m but odometry says {{travelled:.3f}} m: does wheel_radius "
                    f"in {controller_yaml} match the wheels of the robot ({{WHEEL_RADIUS_M}} m)?",
            )


@launch_testing.post_shutdown_test()
class TestCleanExit(unittest.TestCase):
    def test_exit_codes(self, proc_info):
        launch_testing.asserts.assertExitCodes(proc_info)
'''
