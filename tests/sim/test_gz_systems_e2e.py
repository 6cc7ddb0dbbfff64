"""A world built in a temp folder with the Gazebo systems community robots use (OdometryPublisher spelled the
old ignition way, LinearBatteryPlugin, DiffDrive), run by `diffctl sim run` on a real router with real
PyBullet, bridged by `diffctl bridge` and read as ROS messages where a user looks at them."""

from __future__ import annotations

import math
import re
import time
from pathlib import Path

import pytest
from sim_helpers import CAR, EMPTY_WORLD

from diffctl.bus import gz
from diffctl.interfaces import types
from tests.probe import Probe

ODOM = """<plugin filename="libignition-gazebo-odometry-publisher-system.so"
    name="ignition::gazebo::systems::OdometryPublisher">
  <odom_frame>odom</odom_frame><robot_base_frame>base_footprint</robot_base_frame>
  <odom_publish_frequency>30</odom_publish_frequency>
</plugin>"""
BATTERY = """<plugin filename="gz-sim-linearbatteryplugin-system" name="gz::sim::systems::LinearBatteryPlugin">
  <battery_name>linear_battery</battery_name><voltage>12.592</voltage>
  <open_circuit_voltage_constant_coef>12.694</open_circuit_voltage_constant_coef>
  <open_circuit_voltage_linear_coef>-3.1424</open_circuit_voltage_linear_coef>
  <initial_charge>1.1665</initial_charge><capacity>1.2009</capacity><resistance>0.061523</resistance>
  <smooth_current_tau>1.9499</smooth_current_tau><power_load>6.6</power_load><fix_issue_225>true</fix_issue_225>
</plugin>"""


MAGNETOMETER = '<sensor name="compass" type="magnetometer"><topic>mag</topic><update_rate>20</update_rate></sensor>'


def systems_world(folder: Path) -> Path:
    car = CAR.read_text()
    model = car[car.index("<model") : car.rindex("</model>")] + ODOM + BATTERY + "</model>"
    model = re.sub(r'<model name="[^"]*"', '<model name="robot"', model, count=1)
    i = model.index("</link>", model.index('<link name="imu_link">'))
    model = model[:i] + MAGNETOMETER + model[i:]
    world = EMPTY_WORLD.read_text().replace('<world name="empty">', '<world name="systems">')
    i = world.rindex("</world>")
    path = folder / "systems.sdf"
    path.write_text(world[:i] + model + world[i:])
    return path


def wait_for(pred, timeout: float = 30.0, what: str = "condition"):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        v = pred()
        if v:
            return v
        time.sleep(0.05)
    raise AssertionError(f"timed out waiting for {what}")


@pytest.mark.slow
def test_odometry_publisher_and_battery_reach_ros_through_the_bridge(router: str, procs, tmp_path: Path) -> None:
    world = systems_world(tmp_path)
    sim = procs.diffctl("sim", "run", "-r", "--rtf", "4", str(world), cwd=tmp_path)
    bridge = procs.diffctl(
        "bridge",
        "/model/robot/odometry@nav_msgs/msg/Odometry[gz.msgs.Odometry",
        "/model/robot/odometry_with_covariance@nav_msgs/msg/Odometry[gz.msgs.OdometryWithCovariance",
        "/model/robot/battery/linear_battery/state@sensor_msgs/msg/BatteryState[gz.msgs.BatteryState",
        "/cmd_vel@geometry_msgs/msg/Twist]gz.msgs.Twist",  # the car's DiffDrive has <topic>cmd_vel</topic>
        "/model/robot/pose@tf2_msgs/msg/TFMessage[gz.msgs.Pose_V",
        "/mag@sensor_msgs/msg/MagneticField[gz.msgs.Magnetometer",
    )
    node = Probe("systems_probe")
    odom, odom_cov, battery, tf, mag = [], [], [], [], []
    try:
        node.create_subscription("/model/robot/odometry", "nav_msgs/msg/Odometry", odom.append)
        node.create_subscription(
            "/model/robot/battery/linear_battery/state", "sensor_msgs/msg/BatteryState", battery.append
        )
        node.create_subscription("/model/robot/pose", "tf2_msgs/msg/TFMessage", tf.append)
        node.create_subscription("/model/robot/odometry_with_covariance", "nav_msgs/msg/Odometry", odom_cov.append)
        node.create_subscription("/mag", "sensor_msgs/msg/MagneticField", mag.append)
        wait_for(lambda: odom and odom_cov and battery and tf and mag, 60, "odometry, battery, pose and field in ROS")
        # the world sets no <magnetic_field>: sdformat's default, seen by the unturned car as it is
        field = mag[-1].magnetic_field
        assert (field.x, field.y, field.z) == pytest.approx((5.5645e-6, 22.8758e-6, -42.3884e-6), abs=1e-8)
        assert mag[-1].header.frame_id == "robot/imu_link/compass"
        first = battery[-1]
        assert first.power_supply_status == first.POWER_SUPPLY_STATUS_FULL  # not moved yet: not draining
        assert first.percentage == pytest.approx(100 * 1.1665 / 1.2009, rel=1e-5)  # fix_issue_225: 0-100
        assert math.isnan(first.design_capacity)
        o = odom[-1]
        assert (o.header.frame_id, o.child_frame_id) == ("odom", "base_footprint")
        # gz-sim 8's second topic: the same odometry, covariances the (absent) noise's variance
        c = odom_cov[-1]
        assert (c.header.frame_id, c.child_frame_id) == ("odom", "base_footprint")
        assert list(c.pose.covariance) == [0.0] * 36 and list(c.twist.covariance) == [0.0] * 36
        t = tf[-1].transforms[0]
        assert (t.header.frame_id, t.child_frame_id) == ("odom", "base_footprint")
        pub = node.create_publisher("/cmd_vel", "geometry_msgs/msg/Twist")
        cls = types.get_class("geometry_msgs/msg/Twist")
        vec = types.get_class("geometry_msgs/msg/Vector3")
        twist = cls(linear=vec(x=0.3, y=0.0, z=0.0), angular=vec(x=0.0, y=0.0, z=0.0))

        def driving() -> bool:
            pub.publish(twist)
            return odom[-1].twist.twist.linear.x > 0.25 and battery[-1].power_supply_status == 2

        wait_for(driving, 60, "the car driving at 0.3 m/s and its battery discharging")
        before = battery[-1].charge
        wait_for(lambda: battery[-1].charge < before - 1e-6, 30, "charge falling")
        o = odom[-1]
        assert o.twist.twist.linear.x == pytest.approx(0.3, abs=0.03)
        assert o.pose.pose.position.x > 0.05 and o.pose.pose.position.z == 0.0
        b = battery[-1]
        assert 12.0 < b.voltage < 12.7 and 0 < b.current < 6.6 / 12.0  # rising towards 6.6 W / ~12.6 V
    finally:
        node.close()
        for p in (bridge, sim):
            procs.stop(p)


@pytest.mark.slow
def test_image_bridge_from_a_launch_node_brings_the_simulated_camera_to_ros(router: str, procs, tmp_path: Path) -> None:
    # Node(package='ros_gz_image', executable='image_bridge', arguments=['/camera']) runs this command.
    from diffctl.workspace.package_index import executable_argv

    argv = executable_argv("ros_gz_image", "image_bridge")
    assert argv[-2:] == ["diffctl", "image-bridge"]
    world = systems_world(tmp_path)
    sim = procs.diffctl("sim", "run", "-r", "--rtf", "2", str(world), cwd=tmp_path)
    bridge = procs.start([*argv, "/camera"])
    node = Probe("image_probe")
    images = []
    try:
        node.create_subscription("/camera", "sensor_msgs/msg/Image", images.append)
        wait_for(lambda: len(images) >= 2, 60, "two camera frames as sensor_msgs/Image on /camera")
        img = images[-1]
        assert (img.width, img.height, img.encoding, img.step) == (320, 240, "rgb8", 960)
        assert len(img.data) == 320 * 240 * 3 and int(max(img.data)) > 0
        assert img.header.frame_id and "::" not in img.header.frame_id
        assert (img.header.stamp.sec, img.header.stamp.nanosec) > (0, 0)
        assert any(g.node == "ros_gz_image" for g in node.graph.publishers("/camera")) or node.graph.publishers(
            "/camera"
        )
    finally:
        node.close()
        for p in (bridge, sim):
            procs.stop(p)


@pytest.mark.slow
def test_a_triggered_camera_sends_one_frame_per_trigger_and_none_without(router: str, procs, tmp_path: Path) -> None:
    world = systems_world(tmp_path)
    text = world.read_text()
    i = text.index("<camera", text.index('<sensor name="camera"'))
    world.write_text(text[: i + len("<camera>")] + "<triggered>true</triggered>" + text[i + len("<camera>") :])
    sim = procs.diffctl("sim", "run", "-r", "--rtf", "2", str(world), cwd=tmp_path)
    bridge = procs.diffctl("image-bridge", "/camera")
    node = Probe("trigger_probe")
    images, clock = [], []
    try:
        node.create_subscription("/camera", "sensor_msgs/msg/Image", images.append)
        ticks = node.session.declare_subscriber(gz.key("/clock"), lambda s: clock.append(s))  # noqa: F841
        wait_for(lambda: len(clock) > 0 and node.graph.publishers("/camera"), 60, "the sim and the image bridge")
        time.sleep(2.0)  # a second of sim time at 10 Hz: no trigger, no frame
        assert images == []
        trigger = node.session.declare_publisher(gz.key("/camera/trigger"))
        for n in (1, 2):
            # A 230 kB frame is a sample Zenoh drops when its queue stays full (its default congestion control):
            # on a starved machine a lost frame, or a lost trigger, is triggered again.
            for attempt in range(3):
                trigger.put(gz.encode("gz.msgs.Boolean", {"data": True}))
                try:
                    wait_for(lambda n=n: len(images) >= n, 15, f"frame {n} after trigger {n}")
                    break
                except AssertionError:
                    if attempt == 2:
                        raise
            time.sleep(1.0)  # several camera ticks later: still one frame per trigger
            assert len(images) == n
        assert (images[0].width, images[0].height) == (320, 240)
    finally:
        node.close()
        for p in (bridge, sim):
            procs.stop(p)


@pytest.mark.slow
def test_battery_recharge_services_are_listed_and_called_as_gz_service_does(router: str, procs, tmp_path: Path) -> None:
    """gz-sim 8's LinearBatteryPlugin with <enable_recharge>: its recharge/start|stop services are listed by
    `gz service -l/-i` and a request through `gz service -s` starts and stops charging."""
    import os
    import subprocess
    import sys

    world = systems_world(tmp_path)
    recharge = "<enable_recharge>true</enable_recharge><charging_time>2.0</charging_time></plugin>"
    world.write_text(
        world.read_text().replace(
            "<fix_issue_225>true</fix_issue_225>\n</plugin>", "<fix_issue_225>true</fix_issue_225>" + recharge
        )
    )
    assert "<enable_recharge>" in world.read_text()
    sim = procs.diffctl("sim", "run", "-r", str(world), cwd=tmp_path)

    def gz_cli(*args: str) -> str:
        cmd = [sys.executable, "-c", "from diffctl.gz.cli import main; main()", *args]
        return subprocess.run(cmd, capture_output=True, text=True, timeout=30, env=os.environ.copy()).stdout

    base = "/model/robot/battery/linear_battery/recharge"
    wait_for(lambda: f"{base}/start" in gz_cli("service", "-l").split() or sim.poll() is not None, 60, "services")
    assert sim.poll() is None
    listed = gz_cli("service", "-l").split()
    assert f"{base}/stop" in listed and "/world/systems/control" in listed
    info = gz_cli("service", "-i", "-s", f"{base}/start")
    assert "gz.msgs.Boolean, gz.msgs.Empty" in info, info
    assert f"{base}/start" not in gz_cli("topic", "-l").split()  # a service, not a topic

    def status() -> str:
        text = gz_cli("topic", "-e", "-t", "/model/robot/battery/linear_battery/state", "-n", "1")
        return next((line.split(":")[1].strip() for line in text.splitlines() if "power_supply_status" in line), "")

    assert status() != "CHARGING"
    call = ["service", "-s", "--reqtype", "gz.msgs.Boolean", "--reptype", "gz.msgs.Empty", "--req", "data: true"]
    assert gz_cli(*call[:2], f"{base}/start", *call[2:]) == ""  # gz prints nothing for an Empty response
    wait_for(lambda: status() == "CHARGING", 20, "the battery charging")
    gz_cli(*call[:2], f"{base}/stop", *call[2:])
    wait_for(lambda: status() not in ("CHARGING", ""), 20, "charging stopped")
    procs.stop(sim)
