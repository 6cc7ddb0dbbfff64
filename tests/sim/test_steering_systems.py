"""Gazebo's AckermannSteering, MecanumDrive and TrackedVehicle systems drive real PyBullet robots as gz-sim's
kinematics say.

The robots (steering_robots.py) are built the way community SDF builds them. Each commanded twist is checked
against the kinematics gz-sim 8's systems implement (written out here from AckermannSteering.cc and
MecanumDrive.cc): the path the robot takes in the physics, the steering angles and wheel speeds the system
commands, and the odometry it reports against the robot's true pose.
"""

from __future__ import annotations

import math
import threading

import pytest
from sim_helpers import ground, sdf_world, sdf_world_text
from steering_robots import (
    KINGPIN_M,
    STEERING_EFFICIENCY,
    STEERING_LIMIT_RAD,
    TRACK_M,
    TRACKS_SEPARATION_M,
    WHEEL_BASE_M,
    WHEEL_RADIUS_M,
    ackermann_robot,
    mecanum_robot,
    tracked_robot,
)

from diffctl.description.pose import Pose, rpy_from_quat
from diffctl.sim.plugins.ackermann_steering import AckermannSteering
from diffctl.sim.plugins.mecanum_drive import MecanumDrive
from diffctl.sim.plugins.track_controller import TrackController
from diffctl.sim.plugins.tracked_vehicle import TrackedVehicle
from diffctl.sim.runner import Simulation


def advance(sim: Simulation, steps: int) -> None:
    done = threading.Event()
    sim.stepper.set_paused(True)
    sim.stepper.step_n(steps, done.set)
    sim.run(done)


def yaw(p: Pose) -> float:
    return rpy_from_quat(p.quat)[2]


def body_motion(sim: Simulation, name: str, steps: int) -> tuple[float, float, float, Pose]:
    """(forward, sideways, yaw rate) over `steps` physics steps, in the robot frame at their start, and the pose
    at their end."""
    entity = sim.models[name].entity
    p0, t0 = entity.pose(), sim.stepper.sim_time_ns
    advance(sim, steps)
    p1, t1 = entity.pose(), sim.stepper.sim_time_ns
    dt = (t1 - t0) * 1e-9
    dyaw = math.remainder(yaw(p1) - yaw(p0), 2 * math.pi)
    dx, dy = p1.xyz[0] - p0.xyz[0], p1.xyz[1] - p0.xyz[1]
    # on an arc the chord points half the turn ahead of the start heading, and is shorter than the arc
    heading = yaw(p0) + dyaw / 2
    arc = 1.0 if abs(dyaw) < 1e-9 else (dyaw / 2) / math.sin(dyaw / 2)
    c, s = math.cos(heading), math.sin(heading)
    return (c * dx + s * dy) * arc / dt, (-s * dx + c * dy) * arc / dt, dyaw / dt, p1


@pytest.fixture
def car():
    sim = Simulation(sdf_world(ground() + ackermann_robot("car")), rtf=0.0)
    drive = next(p for p in sim.models["car"].plugins if isinstance(p, AckermannSteering))
    advance(sim, 300)
    yield sim, drive
    sim.close()


@pytest.fixture
def omni():
    sim = Simulation(sdf_world(ground() + mecanum_robot("omni")), rtf=0.0)
    drive = next(p for p in sim.models["omni"].plugins if isinstance(p, MecanumDrive))
    advance(sim, 300)
    yield sim, drive
    sim.close()


def test_ackermann_robot_drives_the_commanded_arc_with_gz_sims_steering(car) -> None:
    sim, drive = car
    entity = sim.models["car"].entity
    v, w = 0.5, 0.25
    drive.command(v, w)
    advance(sim, 1500)  # the steering settles (steer_p_gain 20)
    forward, sideways, rate, end = body_motion(sim, "car", 3000)
    radius = v / w  # above the minimum wheel_base / sin(steering_limit): followed as commanded
    assert rate == pytest.approx(w, rel=0.01)
    assert forward == pytest.approx(v, rel=0.02) and abs(sideways) < 0.01
    # AckermannSteering: each steering joint turns about its kingpin, half the kingpin width off the centre line
    left, right = (entity.joint_states([entity.joint(f"{s}_steering_joint")])[0][0] for s in ("left", "right"))
    assert left == pytest.approx(math.atan(WHEEL_BASE_M / (radius - KINGPIN_M / 2)), abs=0.005)
    assert right == pytest.approx(math.atan(WHEEL_BASE_M / (radius + KINGPIN_M / 2)), abs=0.005)
    # the driven wheels as a simple differential: v (1 ± track·tan φ / (2 wheel_base)) / r, φ = atan(L / R)
    spread = TRACK_M * (WHEEL_BASE_M / radius) / (2 * WHEEL_BASE_M)
    wl, wr = (entity.joint_states([entity.joint(f"rear_{s}_joint")])[0][1] for s in ("left", "right"))
    assert wl == pytest.approx(v * (1 - spread) / WHEEL_RADIUS_M, rel=0.01)
    assert wr == pytest.approx(v * (1 + spread) / WHEEL_RADIUS_M, rel=0.01)
    # its odometry (from the wheels and the mean steering angle) follows the true pose
    assert (drive.odom.x_m, drive.odom.y_m) == pytest.approx(end.xyz[:2], abs=0.06)
    assert drive.odom.heading_rad == pytest.approx(yaw(end), abs=0.03)
    assert drive.odom.linear_m_s == pytest.approx(v, rel=0.03)
    assert drive.odom.angular_rad_s == pytest.approx(w, rel=0.05)


def test_ackermann_turn_is_bounded_by_the_steering_limit_and_bad_commands_are_dropped(car) -> None:
    sim, drive = car
    drive.command(0.4, 2.0)  # a 0.2 m radius: the car turns as tight as its steering limit allows
    advance(sim, 1500)
    _, _, rate, _ = body_motion(sim, "car", 2000)
    tightest = WHEEL_BASE_M / math.sin(STEERING_LIMIT_RAD)
    assert rate == pytest.approx(0.4 / tightest, rel=0.03)
    drive.command(0.4, 0.0)
    drive.command(float("nan"), 0.1)  # dropped: straight on
    advance(sim, 1500)
    forward, _, rate, _ = body_motion(sim, "car", 1500)
    assert forward == pytest.approx(0.4, rel=0.02) and abs(rate) < 0.01


def test_ackermann_steering_only_takes_an_angle() -> None:
    extra = "<steering_only>true</steering_only>"
    sim = Simulation(sdf_world(ground() + ackermann_robot("car", extra)), rtf=0.0)
    try:
        drive = next(p for p in sim.models["car"].plugins if isinstance(p, AckermannSteering))
        assert drive.p.topic == "/model/car/steer_angle" and drive.p.steering_only
        drive.command(0.3, 0.0)
        advance(sim, 1500)
        entity = sim.models["car"].entity
        left, right = (entity.joint_states([entity.joint(f"{s}_steering_joint")])[0][0] for s in ("left", "right"))
        s, c = math.sin(0.3), math.cos(0.3)
        assert left == pytest.approx(math.atan(2 * WHEEL_BASE_M * s / (2 * WHEEL_BASE_M * c - TRACK_M * s)), abs=0.005)
        assert right == pytest.approx(math.atan(2 * WHEEL_BASE_M * s / (2 * WHEEL_BASE_M * c + TRACK_M * s)), abs=0.005)
    finally:
        sim.close()


@pytest.mark.parametrize(
    "twist",
    [(0.0, 0.3, 0.0), (0.3, 0.0, 0.0), (0.2, -0.2, 0.0), (0.3, 0.0, 0.4), (0.0, 0.0, -0.5)],
    ids=["sideways", "forward", "diagonal", "arc", "on_the_spot"],
)
def test_mecanum_robot_moves_as_commanded_sideways_and_on_an_arc(omni, twist: tuple[float, float, float]) -> None:
    sim, drive = omni
    entity = sim.models["omni"].entity
    drive.command(*twist)
    advance(sim, 800)
    forward, sideways, rate, end = body_motion(sim, "omni", 2000)
    assert (forward, sideways, rate) == pytest.approx(twist, abs=0.01)
    # MecanumDrive's wheel speeds: (v ∓ v_y ∓ ω (separation + wheelbase)/2) / r per corner
    v, vy, w = twist
    arm = 0.5 * (TRACK_M + WHEEL_BASE_M)
    expected = [(v - vy - w * arm), (v + vy + w * arm), (v + vy - w * arm), (v - vy + w * arm)]
    joints = [entity.joint(f"{c}_joint") for c in ("front_left", "front_right", "rear_left", "rear_right")]
    speeds = [s[1] * WHEEL_RADIUS_M for s in entity.joint_states(joints)]
    assert speeds == pytest.approx(expected, abs=0.002)
    # gz-math's mecanum odometry from those wheels matches the motion and the true pose
    o = drive.odom
    assert (o.linear_m_s, o.lateral_m_s, o.angular_rad_s) == pytest.approx(twist, abs=0.01)
    assert (o.x_m, o.y_m) == pytest.approx(end.xyz[:2], abs=0.03)
    assert o.heading_rad == pytest.approx(yaw(end), abs=0.01)


@pytest.mark.slow
def test_mecanum_and_joint_systems_over_their_gz_topics_through_the_bridge(router: str, procs, tmp_path) -> None:
    """`diffctl sim run` with the systems on their default gz topics; ROS commands reach them through
    ros_gz_bridge's type pairs (Twist, Float64 → gz.msgs.Double) and their odometry comes back."""
    import time

    from test_joint_systems import arm, plugin

    from diffctl.interfaces import types
    from tests.probe import Probe

    jpc = "<joint_name>j1</joint_name><topic>j1_cmd</topic>"
    arm_model = arm(
        # (its default topic /model/arm/joint/j1/0/cmd_pos is no valid ROS name: ROS users give a <topic>)
        plugin("joint-position-controller", "JointPositionController", jpc)
        + plugin("joint-state-publisher", "JointStatePublisher", "<joint_name>j1</joint_name>")
    ).replace("<model name='arm'>", "<model name='arm'><pose>0 5 0 0 0 0</pose>")
    world = tmp_path / "systems.sdf"
    world.write_text(sdf_world_text(ground() + mecanum_robot("omni") + arm_model))
    sim = procs.diffctl("sim", "run", "-r", "--rtf", "0", str(world), cwd=tmp_path)
    bridge = procs.diffctl(
        "bridge",
        "/model/omni/cmd_vel@geometry_msgs/msg/Twist]gz.msgs.Twist",
        "/model/omni/odometry@nav_msgs/msg/Odometry[gz.msgs.Odometry",
        "/j1_cmd@std_msgs/msg/Float64]gz.msgs.Double",
        "/world/test/model/arm/joint_state@sensor_msgs/msg/JointState[gz.msgs.Model",
    )
    node = Probe("systems_probe")
    odom, joints = [], []
    try:
        node.create_subscription("/model/omni/odometry", "nav_msgs/msg/Odometry", odom.append)
        node.create_subscription("/world/test/model/arm/joint_state", "sensor_msgs/msg/JointState", joints.append)
        twist_pub = node.create_publisher("/model/omni/cmd_vel", "geometry_msgs/msg/Twist")
        position_pub = node.create_publisher("/j1_cmd", "std_msgs/msg/Float64")
        Twist, Vector3 = types.get_class("geometry_msgs/msg/Twist"), types.get_class("geometry_msgs/msg/Vector3")
        sideways = Twist(linear=Vector3(x=0.0, y=0.3, z=0.0), angular=Vector3(x=0.0, y=0.0, z=0.0))
        target = types.get_class("std_msgs/msg/Float64")(data=0.7)
        deadline = time.monotonic() + 60
        def done() -> bool:
            moved = odom and odom[-1].pose.pose.position.y > 0.5
            return bool(moved and joints and abs(joints[-1].position[0] - 0.7) < 0.01)

        while not done():
            assert time.monotonic() < deadline, (
                f"went sideways / joint: {odom[-1].pose.pose.position if odom else None} / "
                f"{joints[-1].position if joints else None}"
            )
            twist_pub.publish(sideways)
            position_pub.publish(target)
            time.sleep(0.05)
        o = odom[-1]
        assert o.header.frame_id == "omni/odom" and o.child_frame_id == "omni/chassis"
        assert o.twist.twist.linear.y == pytest.approx(0.3, abs=0.02) and abs(o.pose.pose.position.x) < 0.02
    finally:
        node.close()
        for p in (bridge, sim):
            procs.stop(p)


def test_tracked_vehicle_drives_straight_and_turns_about_its_commanded_centre() -> None:
    """TrackedVehicle splits a twist into track speeds v ∓ ω·separation/(2·efficiency) and a centre of rotation at
    v/ω on the body's y axis; the tracks' contacts, steered about it as gz-sim's TrackController steers them, turn
    the vehicle about that centre (the radius commanded) at the rate their frictions settle on: the command's, to
    within what gz-sim's own test allows, for a vehicle whose steering efficiency suits its tracks."""
    sim = Simulation(sdf_world(ground() + tracked_robot("tank")), rtf=0.0)
    try:
        rt = sim.models["tank"]
        vehicle = next(p for p in rt.plugins if isinstance(p, TrackedVehicle))
        tracks = {p.link: p for p in rt.plugins if isinstance(p, TrackController)}
        left, right = tracks["left_track"], tracks["right_track"]
        assert left.velocity_topic == "/model/tank/link/left_track/track_cmd_vel"
        advance(sim, 300)
        for v in (0.4, -0.3):
            vehicle.command(v, 0.0)
            advance(sim, 500)
            forward, sideways, rate, _ = body_motion(sim, "tank", 1000)
            assert (forward, sideways, rate) == pytest.approx((v, 0.0, 0.0), abs=0.005)
            assert vehicle.odom.linear_m_s == pytest.approx(v, abs=1e-6)
        for v, w in ((0.0, 0.5), (0.5, 0.2), (0.3, -0.3), (-0.3, 0.4)):
            vehicle.command(v, w)
            advance(sim, 500)
            turn = w * TRACKS_SEPARATION_M / (2 * STEERING_EFFICIENCY)
            assert (left.speed, right.speed) == pytest.approx((v - turn, v + turn))
            forward, sideways, rate, _ = body_motion(sim, "tank", 1000)
            assert rate == pytest.approx(w, rel=0.15), (v, w)
            assert forward == pytest.approx(rate * v / w, abs=0.01) and abs(sideways) < 0.01, (v, w)
            # gz-sim's odometry: the commanded track speeds as a differential drive's
            assert vehicle.odom.angular_rad_s == pytest.approx(2 * turn / TRACKS_SEPARATION_M, abs=1e-6)
        vehicle.command(5.0, 0.0)  # past the tracks' own max_velocity (1 m/s)
        advance(sim, 100)
        assert (left.speed, right.speed) == (1.0, 1.0)
    finally:
        sim.close()


@pytest.mark.slow
def test_tracked_vehicle_on_its_gz_topics(router: str) -> None:
    """A twist on TrackedVehicle's <topic> drives the tracks; its odometry (the commanded track speeds as a
    differential drive's, gz-sim's) and each TrackController's (the track's speed) come back on their default
    topics; a steering efficiency on /model/<m>/steering_efficiency changes how far apart the tracks run."""
    from diffctl.bus import gz, open_session
    from tests.waiting import wait_for

    session = open_session()
    extra = "<topic>/tank/drive</topic><child_frame_id>tank/chassis</child_frame_id>"
    sim = Simulation(
        sdf_world(ground() + tracked_robot("tank", vehicle_extra=extra)), rtf=0.0, paused=False, session=session
    )
    stop = threading.Event()
    thread = threading.Thread(target=sim.run, args=(stop,), daemon=True)
    got: dict[str, list[dict]] = {"/model/tank/odometry": [], "/model/tank/link/right_track/odometry": []}
    subs = [
        session.declare_subscriber(gz.key(topic), lambda s, out=out: out.append(gz.decode(s.payload.to_bytes())[1]))
        for topic, out in got.items()
    ]
    drive = session.declare_publisher(gz.key("/tank/drive"))
    efficiency = session.declare_publisher(gz.key("/model/tank/steering_efficiency"))
    try:
        thread.start()
        v, w = 0.4, 0.3
        twist = gz.encode("gz.msgs.Twist", {"linear": {"x": v}, "angular": {"z": w}})
        vehicle, track = got.values()

        def speeds(eff: float) -> bool:
            if not (vehicle and track):
                return False
            o, t = vehicle[-1]["twist"], track[-1]["twist"]
            return (
                abs(o["linear"]["x"] - v) < 1e-6
                and abs(o["angular"]["z"] - w / eff) < 1e-6
                and abs(t["linear"]["x"] - (v + w * TRACKS_SEPARATION_M / (2 * eff))) < 1e-6
            )

        assert wait_for(lambda: speeds(STEERING_EFFICIENCY), 30, lambda: drive.put(twist)), (vehicle[-1:], track[-1:])
        header = vehicle[-1]["header"]
        assert (gz.header_value(header, "frame_id"), gz.header_value(header, "child_frame_id")) == (
            "tank/odom",
            "tank/chassis",
        )
        assert track[-1]["pose"]["position"]["x"] > 0.0  # the right track's travel
        assert wait_for(
            lambda: speeds(1.0), 30, lambda: efficiency.put(gz.encode("gz.msgs.Double", {"data": 1.0}))
        ), (vehicle[-1:], track[-1:])
    finally:
        for s in subs:
            s.undeclare()
        drive.undeclare()
        efficiency.undeclare()
        stop.set()
        thread.join(10)
        sim.close()
        session.close()
