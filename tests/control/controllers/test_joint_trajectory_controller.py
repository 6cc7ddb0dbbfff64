"""joint_trajectory_controller driven directly (a real client node), with the scenarios and expected values of
upstream's test_trajectory_controller.cpp and test_tolerances.cpp (ros2_controllers jazzy): three joints starting
at 1.1, 2.1, 3.1, updates every 10 ms, "ideal hardware" mirroring the commands into the states unless the test
keeps them apart."""

from __future__ import annotations

import math

import pytest
from controller_harness import NS, START_NS, activate, configure, hand_interfaces, make_controller, update

from diffctl.client.interfaces import cls
from diffctl.control.controllers import joint_trajectory_tolerances as tol
from diffctl.control.controllers.joint_trajectory_controller import JointTrajectoryController
from diffctl.control.lifecycle import State
from diffctl.errors import ParameterError

pytestmark = pytest.mark.usefixtures("client_bus")

NAME = "joint_trajectory_controller"
TOPIC = f"/{NAME}/joint_trajectory"
JOINTS = ["joint1", "joint2", "joint3"]
INITIAL = [1.1, 2.1, 3.1]
COMMON_THRESHOLD = 0.001
CONTINUOUS_URDF = """<robot name="rrrbot"><link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/>
<joint name="joint1" type="continuous"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/></joint>
<joint name="joint2" type="revolute"><parent link="l1"/><child link="l2"/><axis xyz="0 0 1"/>
<limit lower="-3" upper="3" effort="10" velocity="2"/></joint>
<joint name="joint3" type="revolute"><parent link="l2"/><child link="l3"/><axis xyz="0 0 1"/>
<limit lower="-3" upper="3" effort="10" velocity="2"/></joint></robot>"""


class Rig:
    """A configured and activated controller with its handles; `run` updates it as upstream's updateControllerAsync
    (every 10 ms from `start` to `start + duration` inclusive), mirroring commands into states unless `separate`."""

    def __init__(self, command=("position",), state=("position", "velocity"), params=None, description="",
                 separate=False) -> None:
        # upstream's fixture: non-zero end velocities allowed, antiwindup "none", velocity feed-forward 1, P 0
        p = {"joints": JOINTS, "command_interfaces": list(command), "state_interfaces": list(state),
             "allow_nonzero_velocity_at_trajectory_end": True}
        for j in JOINTS:
            p |= {f"gains.{j}.antiwindup_strategy": "none", f"gains.{j}.ff_velocity_scale": 1.0,
                  f"gains.{j}.i_clamp": 1000.0}
        p |= params or {}
        self.c = make_controller(JointTrajectoryController, NAME, p, robot_description=description)
        configure(self.c)
        values = {f"{j}/position": INITIAL[i] for i, j in enumerate(JOINTS)}
        self.cmd, self.state = hand_interfaces(self.c, values)
        activate(self.c)
        self.separate = separate
        self.time_ns = START_NS

    def values(self, kind: str, which: str = "cmd") -> list[float]:
        table = self.cmd if which == "cmd" else self.state
        return [table[f"{j}/{kind}"].value for j in JOINTS]

    def run(self, duration_s: float) -> None:
        end = self.time_ns + round(duration_s * NS)
        while self.time_ns <= end:
            update(self.c, self.time_ns, 0.01)
            if not self.separate:
                for name, h in self.cmd.items():
                    if name in self.state:
                        self.state[name].value = h.value
            self.time_ns += 10_000_000
        self.time_ns = end

    def send(self, names, positions, t_s=0.25, velocities=(), accelerations=(), effort=(), stamp_ns=0) -> None:
        points = []
        for k, pos in enumerate(positions):
            t_ns = round(t_s * (k + 1) * NS)
            point = {"positions": list(pos), "time_from_start": {"sec": t_ns // NS, "nanosec": t_ns % NS}}
            for field, rows in (("velocities", velocities), ("accelerations", accelerations), ("effort", effort)):
                if rows:
                    point[field] = list(rows[k])
            points.append(point)
        self.c.probe.deliver(TOPIC, {"joint_names": list(names), "points": points,
                                     "header": {"stamp": {"sec": stamp_ns // NS, "nanosec": stamp_ns % NS}}})


def test_interfaces_and_parameters_as_declared() -> None:
    rig = Rig(command=("position", "velocity"), state=("position", "velocity", "acceleration"))
    c = rig.c
    assert c.command_interface_configuration().names == [f"{j}/{k}" for j in JOINTS for k in ("position", "velocity")]
    assert c.state_interface_configuration().names == [
        f"{j}/{k}" for j in JOINTS for k in ("position", "velocity", "acceleration")]
    node = c.get_node()
    assert node.get_parameter("gains.joint2.p").value == 0.0
    assert node.get_parameter("constraints.goal_time").value == 0.0
    assert node.describe_parameter("joints").read_only
    assert node.describe_parameter("constraints.joint1.max_deceleration_on_cancel").floating_point_range[0] \
        .from_value == 0.0
    assert {f"/{NAME}/controller_state"} <= c.probe.publishers
    assert not c.use_closed_loop_pid_adapter()


@pytest.mark.parametrize(("params", "field", "why"), [
    ({"command_interfaces": ["velocity", "acceleration"]}, "command_interfaces",
     "'velocity' command interface can be used either alone or 'position' command interface has to be present"),
    ({"command_interfaces": ["position", "velocity", "effort"]}, "command_interfaces",
     "'effort' command interface has to be used alone or with a 'position' interface"),
    ({"command_interfaces": ["bad_name"]}, "command_interfaces", "is not one of"),
    ({"command_interfaces": []}, "command_interfaces", "more than 0"),
    ({"state_interfaces": ["velocity"]}, "state_interfaces", "'velocity' state interface cannot be used"),
    ({"joints": ["a", "a"]}, "joints", "more than once"),
    ({"interpolation_method": "cubic"}, "interpolation_method", "is not one of"),
    ({"gains.joint1.antiwindup_strategy": "clamp"}, "gains.joint1.antiwindup_strategy", "is not one of"),
])
def test_bad_parameters_are_refused_naming_the_field(params, field, why) -> None:
    p = {"joints": JOINTS, "command_interfaces": ["position"], "state_interfaces": ["position"], **params}
    with pytest.raises(ParameterError) as e:
        make_controller(JointTrajectoryController, NAME, p)
    assert e.value.field == f"{NAME}.{field}" and why in str(e.value)


def test_velocity_alone_needs_position_and_velocity_states() -> None:
    c = make_controller(JointTrajectoryController, NAME,
                        {"joints": JOINTS, "command_interfaces": ["velocity"], "state_interfaces": ["position"]})
    assert c.on_configure(State.UNCONFIGURED).name == "FAILURE"


def test_holds_its_start_then_follows_a_jumbled_trajectory() -> None:
    # hold_on_startup, then test_jumbled_joint_order (position + velocity commands)
    rig = Rig(command=("position", "velocity"))
    rig.run(0.25)
    assert rig.c.has_active_trajectory() and rig.values("position") == pytest.approx(INITIAL, abs=COMMON_THRESHOLD)
    target, dt, jumble = [1.0, 2.0, 3.0], 0.25, [1, 2, 0]
    names = [JOINTS[k] for k in jumble]
    pos = [target[k] for k in jumble]
    vel = [(pos[d] - rig.cmd[f"{JOINTS[jumble[d]]}/position"].value) / dt for d in range(3)]
    acc = [(vel[d] - rig.cmd[f"{JOINTS[jumble[d]]}/velocity"].value) / dt for d in range(3)]
    rig.send(names, [pos], dt, [vel], [acc])
    rig.run(dt)
    assert rig.values("position") == pytest.approx(target, abs=COMMON_THRESHOLD)
    assert all(v < 0.0 for v in rig.values("velocity"))


def test_a_partial_goal_keeps_the_other_joint_where_it_is_commanded() -> None:
    # test_partial_joint_list: joints [joint2, joint1] to (2.0, 1.0); joint3 stays
    rig = Rig(command=("position", "velocity"), params={"allow_partial_joints_goal": True})
    rig.run(0.01)
    dt = 0.25
    vel = [(2.0 - INITIAL[1]) / dt, (1.0 - INITIAL[0]) / dt]
    rig.send(["joint2", "joint1"], [[2.0, 1.0]], dt, [vel], [[v / dt for v in vel]])
    rig.run(dt)
    assert rig.values("position") == pytest.approx([1.0, 2.0, INITIAL[2]], abs=COMMON_THRESHOLD)
    assert rig.values("velocity")[2] == pytest.approx(0.0, abs=COMMON_THRESHOLD)
    # test_partial_joint_list_not_allowed: the same message is refused
    other = Rig(command=("position", "velocity"))
    other.send(["joint2", "joint1"], [[2.0, 1.0]], dt)
    other.run(dt)
    assert other.values("position") == pytest.approx(INITIAL, abs=COMMON_THRESHOLD)
    assert "Joints on incoming trajectory don't match the controller joints." in other.c.probe.log.text("ERROR")


POINTS = [[3.3, 4.4, 5.5], [7.7, 8.8, 9.9], [10.10, 11.11, 12.12]]
VELOCITIES = [[0.01] * 3, [0.05] * 3, [0.06] * 3]


@pytest.mark.parametrize("command", [("position",), ("velocity",), ("effort",)])
def test_path_tolerance_violated_holds_the_measured_position(command) -> None:
    # test_state_tolerances_fail: trajectory tolerance 1e-4, states kept apart from the commands, kp 1
    params = {f"constraints.{j}.trajectory": 0.0001 for j in JOINTS} | {f"gains.{j}.p": 1.0 for j in JOINTS}
    rig = Rig(command=command, params=params, separate=True)
    rig.send(JOINTS, POINTS, 0.1, VELOCITIES)
    rig.run(0.1)
    assert rig.c.state_reference.positions == pytest.approx(INITIAL)  # holding what the joints measure
    assert "Holding position due to state tolerance violation" in rig.c.probe.log.text("ERROR")
    if command == ("position",):
        assert rig.values("position") == pytest.approx(INITIAL, abs=COMMON_THRESHOLD)


def test_goal_time_exceeded_holds_and_keeps_holding() -> None:
    # test_goal_tolerances_fail: goal tolerance 0.1, goal_time 1e-6
    params = {f"constraints.{j}.goal": 0.1 for j in JOINTS} | {"constraints.goal_time": 0.000001}
    rig = Rig(params=params, separate=True)
    rig.send(JOINTS, POINTS, 0.1, VELOCITIES)
    rig.run(0.4)
    assert rig.values("position") == pytest.approx(INITIAL, abs=COMMON_THRESHOLD)
    assert "Exceeded goal_time_tolerance: holding position..." in rig.c.probe.log.text("ERROR")
    rig.state["joint1/position"].value = -3.3
    rig.run(0.1)
    assert rig.values("position") == pytest.approx(INITIAL, abs=COMMON_THRESHOLD)


def test_command_timeout_after_the_last_point_holds_it() -> None:
    # accept_correct_cmd_timeout / decline_false_cmd_timeout, then timeout (position commands)
    assert Rig(params={"cmd_timeout": 1.0, "constraints.goal_time": 2.0}).c._cmd_timeout_s == 0.0
    assert Rig(params={"cmd_timeout": 3.0, "constraints.goal_time": 2.0}).c._cmd_timeout_s == 3.0
    rig = Rig(params={"cmd_timeout": 0.1})
    rig.send(JOINTS, POINTS, 0.25, VELOCITIES)
    rig.run(0.75)
    assert len(rig.c._trajectory.points) == 3
    rig.run(0.25)
    assert len(rig.c._trajectory.points) == 1 and "Aborted due to command timeout" in rig.c.probe.log.text("WARN")
    assert rig.values("position") == pytest.approx(POINTS[2], abs=COMMON_THRESHOLD)


def test_without_timeout_the_trajectory_stays() -> None:
    # no_timeout: after 1 s the reference is the last point, still moving (its velocity 0.06 > 0)
    rig = Rig(command=("position", "velocity"))
    rig.send(JOINTS, POINTS, 0.25, VELOCITIES)
    rig.run(1.0)
    assert rig.c.state_reference.positions == pytest.approx(POINTS[2], abs=1e-2)
    assert all(v > 0.0 for v in rig.c.state_reference.velocities)


def test_velocity_commands_come_from_the_pid_and_feed_forward() -> None:
    rig = Rig(command=("velocity",), params={f"gains.{j}.p": 2.0 for j in JOINTS}, separate=True)
    assert rig.c.use_closed_loop_pid_adapter()
    rig.send(JOINTS, [[1.6, 2.6, 3.6]], 1.0)
    rig.run(0.0)
    # one cycle in: command = desired velocity (next sample) + 2 · (desired − measured position) now
    ahead = rig.c._command_next
    error = rig.c.state_error.positions
    assert rig.values("velocity") == pytest.approx([ahead.velocities[i] + 2.0 * error[i] for i in range(3)])
    rig.run(1.5)
    assert rig.values("velocity") == pytest.approx([2.0 * 0.5] * 3, abs=1e-9)  # stuck joints: P on 0.5 rad


def test_continuous_joints_wrap_the_error() -> None:
    # compute_error_angle_wraparound_true: joint1 continuous in the description, 3π/2 ahead → -π/2
    rig = Rig(command=("position", "velocity"), description=CONTINUOUS_URDF)
    assert rig.c._wraps == [True, False, False]
    current = rig.c.state_feedback.copy()
    current.positions, current.velocities = [3.3, 4.4, 6.6], [0.01] * 3
    desired = current.copy()
    desired.positions[0] += 3.0 * math.pi / 2
    for i in range(3):
        rig.c._compute_error(i, current, desired)
    assert rig.c.state_error.positions == pytest.approx([3 * math.pi / 2 - 2 * math.pi, 0.0, 0.0])


@pytest.mark.parametrize(("change", "text"), [
    ({"joint_names": []}, "Joints on incoming trajectory don't match the controller joints."),
    ({"points": []}, "Empty trajectory received."),
    ({"joint_names": ["joint1", "joint2", "joint4"]}, "Incoming joint joint4 doesn't match the controller's joints."),
    ({"points": [{"positions": [1.0, 2.0], "time_from_start": {"sec": 1}}]},
     "Mismatch between joint_names size (3) and positions (2) at point #0."),
    ({"points": [{"positions": [1.0, 2.0, 3.0], "velocities": [0.0, 0.0, 1.0], "time_from_start": {"sec": 1}}]},
     "Velocity of last trajectory point of joint joint3 is not zero: 1.000000000000000"),
    ({"points": [{"positions": [1.0, 2.0, 3.0], "time_from_start": {"sec": 2}},
                 {"positions": [1.0, 2.0, 3.0], "time_from_start": {"sec": 1}}]},
     "Time between points 0 and 1 is not strictly increasing, it is 2.000000 and 1.000000 respectively"),
    ({"points": [{"positions": [1.0, 2.0, 3.0], "effort": [1.0, 1.0, 1.0], "time_from_start": {"sec": 1}}]},
     "Trajectories with effort fields are only supported for controllers using the 'effort' command interface."),
    ({"points": [{"positions": [1.0, float("nan"), 3.0], "time_from_start": {"sec": 1}}]},
     "Point #0 has a non-finite positions value (nan)"),
    ({"header": {"stamp": {"sec": 50}}}, "Received trajectory with non-zero start time (50.000000) that ends in "
     "the past (51.000000)"),
])
def test_invalid_trajectories_are_refused(change, text) -> None:
    # invalid_message
    rig = Rig(params={"allow_nonzero_velocity_at_trajectory_end": False})
    msg = {"joint_names": JOINTS, "points": [{"positions": [5.0, 5.0, 5.0], "time_from_start": {"sec": 1}}]} | change
    rig.c.probe.deliver(TOPIC, msg)
    rig.run(0.05)
    assert text in rig.c.probe.log.text("ERROR")
    assert rig.values("position") == pytest.approx(INITIAL)


def test_query_state_samples_the_future() -> None:
    rig = Rig()
    rig.send(JOINTS, [[2.1, 3.1, 4.1]], 1.0)
    rig.run(0.1)
    srv = cls("control_msgs/srv/QueryTrajectoryState")
    request = srv.Request()
    half = START_NS + NS // 2
    request.time.sec, request.time.nanosec = divmod(half, NS)
    response = rig.c._on_query_state(request, srv.Response())
    assert response.success and response.name == JOINTS
    assert list(response.position) == pytest.approx([1.6, 2.6, 3.6])
    request.time.sec += 5  # past the end
    assert not rig.c._on_query_state(request, srv.Response()).success
    assert "Requested sample time precedes the current trajectory end time." in rig.c.probe.log.text("ERROR")


def test_state_message_published_every_update() -> None:
    rig = Rig(command=("position",), state=("position", "velocity"))
    rig.run(0.02)
    sent = rig.c.probe.sent(f"/{NAME}/controller_state")
    assert len(sent) == 3
    last = sent[-1]
    assert last["joint_names"] == JOINTS and last["feedback"]["positions"] == pytest.approx(INITIAL)
    assert last["output"]["positions"] == pytest.approx(INITIAL) and last["speed_scaling_factor"] == 1.0
    assert len(last["reference"]["accelerations"]) == 3 and last["output"]["velocities"] == []


def tolerance(name, p, v, a):
    return tol.JointToleranceRequest(name, p, v, a)


def test_goal_tolerances_override_erase_or_fall_back_to_the_defaults() -> None:
    # test_tolerances.cpp: defaults 0.1 path/goal position, stopped velocity 0.01, goal time 0
    defaults = tol.from_parameters(JOINTS, [0.1] * 3, [0.1] * 3, 0.01, 0.0)
    path = [tolerance(j, 0.2, 0.3, 0.4) for j in JOINTS]
    goal = [tolerance("joint2", 1.2, 2.2, 3.2), tolerance("joint3", 1.3, 2.3, 3.3), tolerance("joint1", 1.1, 2.1, 3.1)]
    active = tol.for_goal(defaults, tol.GoalTolerances(2.0, path, goal), JOINTS)
    assert active.goal_time_s == 2.0
    assert active.state == (tol.StateTolerance(0.2, 0.3, 0.4),) * 3
    assert [(t.position, t.velocity, t.acceleration) for t in active.goal_state] == \
        [(1.1, 2.1, 3.1), (1.2, 2.2, 3.2), (1.3, 2.3, 3.3)]
    erased = tol.for_goal(defaults, tol.GoalTolerances(-1.0, [tolerance(j, -1, -1, -1) for j in JOINTS],
                                                       [tolerance(j, -1, -1, -1) for j in JOINTS]), JOINTS)
    assert erased.goal_time_s == 0.0 and erased.state == erased.goal_state == (tol.StateTolerance(),) * 3
    for bad in (tol.GoalTolerances(-123.0, [tolerance("joint1", 0, 0, 0)]),
                tol.GoalTolerances(3.0, [tolerance("joint1", -123.0, 0, 0)]),
                tol.GoalTolerances(3.0, [], [tolerance("joint1", 0, -123.0, 0)]),
                tol.GoalTolerances(3.0, [tolerance("joint4", 0.1, 0, 0)])):
        errors: list[str] = []
        assert tol.for_goal(defaults, bad, JOINTS, errors) is defaults and errors
