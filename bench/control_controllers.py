"""The update cost of ros2_controllers' controllers beyond the tutorial's two: each controller on its own client
node (a real router), configured and activated on mock handles, then `update(time, period)` run 2000 times at
100 Hz of simulated time, back to back, the realtime publishers held (so what is timed is the controller's own
work, the hand-off of what it publishes included, not the publishing thread's).

Keys, mean microseconds per update (`control_update_us_<controller>`):
  joint_trajectory_controller      6 joints, position commands, position + velocity states, following a 30 s
                                   two-waypoint trajectory (spline sampling twice per cycle, state message)
  imu_sensor_broadcaster, range_sensor_broadcaster, force_torque_sensor_broadcaster
  joint_group_position_controller  3 joints, a command received
  mecanum_drive_controller, ackermann_steering_controller, pid_controller (2 DoF, position + velocity)
                                   chained, a reference written every cycle
  tricycle_controller              a command received (timeout 1 h)
  parallel_gripper_action_controller   no goal
Each figure is the best of three runs of 2000 updates (the controller keeps running from one to the next), timed
in the thread's CPU time: on a shared machine, waiting for a core or the GIL is not the controller's cost.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

N_UPDATES = 2000
PERIOD_NS = 10_000_000


def _controller(cls_: type, name: str, params: dict[str, Any]) -> Any:
    from diffctl.client.node import Node
    from diffctl.client.parameter import Parameter
    from diffctl.control.controller_interface import ControllerInterfaceParams
    from diffctl.control.lifecycle import State

    overrides = [Parameter(k, value=v) for k, v in params.items()]
    node = Node(name, parameter_overrides=overrides, use_global_arguments=False, enable_rosout=False)
    c = cls_()
    c.init(ControllerInterfaceParams(name, "", 100, node))
    c._state = State.UNCONFIGURED
    c.on_configure(State.UNCONFIGURED)
    if c.is_chainable():
        c.export_reference_interfaces()
        c.export_state_interfaces()
    return c


def _activate(c: Any, values: dict[str, float], chained: bool = False) -> None:
    from diffctl.control.controller_interface import CommandInterface, StateInterface
    from diffctl.control.lifecycle import State

    c.command_interfaces = [CommandInterface(n, values.get(n, 0.0)) for n in c.command_interface_configuration().names]
    c.state_interfaces = [StateInterface(n, values.get(n, 0.0)) for n in c.state_interface_configuration().names]
    if chained:
        c.set_chained_mode(True)
    c.on_activate(State.INACTIVE)
    c._state = State.ACTIVE


def _mean_update_us(c: Any, before: Callable[[], None] | None = None, rounds: int = 3) -> float:
    """The mean cost of an update over N_UPDATES cycles, the best of `rounds` such runs (the machine is shared)."""
    return min(_one_round(c, before) for _ in range(rounds))


def _one_round(c: Any, before: Callable[[], None] | None) -> float:
    from diffctl.client.clock_type import ClockType
    from diffctl.client.duration import Duration
    from diffctl.client.ros_time import Time
    from diffctl.control import realtime_publisher

    period = Duration(nanoseconds=PERIOD_NS)
    t_ns = c.__dict__.setdefault("_bench_t_ns", 100 * 1_000_000_000)
    spent = 0
    # Samples queue without waking the publishing thread until the round ends (the manager wakes it once per
    # cycle, after all its controllers): the figure is the controller's own work, not the GIL's contention.
    held = realtime_publisher.hold()
    for _ in range(N_UPDATES):
        t_ns += PERIOD_NS
        if before is not None:
            before()
        now = Time(nanoseconds=t_ns, clock_type=ClockType.ROS_TIME)
        t0 = time.thread_time_ns()
        c.update(now, period)
        spent += time.thread_time_ns() - t0
    realtime_publisher.release(held)
    c._bench_t_ns = t_ns
    return round(spent / N_UPDATES / 1000, 1)


def _jtc() -> float:
    from diffctl.client.interfaces import cls
    from diffctl.control.controllers.joint_trajectory_controller import JointTrajectoryController

    joints = [f"joint{i}" for i in range(1, 7)]
    c = _controller(JointTrajectoryController, "joint_trajectory_controller", {
        "joints": joints, "command_interfaces": ["position"], "state_interfaces": ["position", "velocity"]})
    _activate(c, {})
    msg = cls("trajectory_msgs/msg/JointTrajectory")()
    msg.joint_names = joints
    for k, t_s in ((1, 15), (2, 30)):
        point = cls("trajectory_msgs/msg/JointTrajectoryPoint")()
        point.positions = [0.5 * k] * 6
        point.time_from_start.sec = t_s
        msg.points.append(point)
    c._on_trajectory(msg)
    return _mean_update_us(c)


def _sensors() -> dict[str, float]:
    from diffctl.control.controllers.force_torque_sensor_broadcaster import ForceTorqueSensorBroadcaster
    from diffctl.control.controllers.imu_sensor_broadcaster import IMUSensorBroadcaster
    from diffctl.control.controllers.range_sensor_broadcaster import RangeSensorBroadcaster

    out = {}
    for key, cls_, params in (
        ("imu_sensor_broadcaster", IMUSensorBroadcaster, {"sensor_name": "imu", "frame_id": "imu_link"}),
        ("range_sensor_broadcaster", RangeSensorBroadcaster, {"sensor_name": "range", "frame_id": "range_link"}),
        ("force_torque_sensor_broadcaster", ForceTorqueSensorBroadcaster, {"sensor_name": "fts", "frame_id": "fts"}),
    ):
        c = _controller(cls_, key, params)
        _activate(c, {})
        out[key] = _mean_update_us(c)
    return out


def _joint_group() -> float:
    from diffctl.control.controllers.joint_group_controllers import JointGroupPositionController

    c = _controller(JointGroupPositionController, "joint_group_position_controller", {"joints": ["a", "b", "c"]})
    _activate(c, {})
    c._command = (0.1, 0.2, 0.3)
    return _mean_update_us(c)


def _chained(key: str, cls_: type, params: dict[str, Any], reference: list[float]) -> float:
    c = _controller(cls_, key, params)
    _activate(c, {n: 0.1 for n in c.state_interface_configuration().names}, chained=True)

    def feed() -> None:
        for handle, value in zip(c.reference_interfaces, reference, strict=False):
            handle.value = value

    return _mean_update_us(c, feed)


def _drives() -> dict[str, float]:
    from diffctl.control.controllers.ackermann_steering_controller import AckermannSteeringController
    from diffctl.control.controllers.mecanum_drive_controller import MecanumDriveController
    from diffctl.control.controllers.pid_controller import PidController

    mecanum = {"front_left_wheel_command_joint_name": "fl", "front_right_wheel_command_joint_name": "fr",
               "rear_right_wheel_command_joint_name": "rr", "rear_left_wheel_command_joint_name": "rl",
               "kinematics.wheels_radius": 0.05, "kinematics.sum_of_robot_center_projection_on_X_Y_axis": 0.3}
    ackermann = {"traction_joints_names": ["rr", "rl"], "steering_joints_names": ["sr", "sl"], "wheelbase": 0.8,
                 "traction_track_width": 0.6, "traction_wheels_radius": 0.15}
    pid = {"dof_names": ["j1", "j2"], "command_interface": "velocity",
           "reference_and_state_interfaces": ["position", "velocity"], "gains.j1.p": 1.0, "gains.j2.p": 1.0,
           "gains.j1.antiwindup_strategy": "none", "gains.j2.antiwindup_strategy": "none"}
    return {
        "mecanum_drive_controller": _chained("mecanum_drive_controller", MecanumDriveController, mecanum,
                                             [0.2, 0.1, 0.3]),
        "ackermann_steering_controller": _chained("ackermann_steering_controller", AckermannSteeringController,
                                                  ackermann, [0.5, 0.25]),
        "pid_controller": _chained("pid_controller", PidController, pid, [1.0, 2.0, 0.0, 0.0]),
    }


def _tricycle() -> float:
    from diffctl.control.controllers.tricycle_controller import TricycleController

    c = _controller(TricycleController, "tricycle_controller", {
        "traction_joint_name": "traction", "steering_joint_name": "steering", "wheelbase": 0.8,
        "wheel_radius": 0.15, "cmd_vel_timeout": 3_600_000})
    _activate(c, {})
    c._command = (100 * 1_000_000_000, 0.5, 0.25)
    return _mean_update_us(c)


def _gripper() -> float:
    from diffctl.control.controllers.parallel_gripper_action_controller import GripperActionController

    c = _controller(GripperActionController, "parallel_gripper_action_controller", {"joint": "gripper"})
    _activate(c, {})
    return _mean_update_us(c)


def measure() -> dict[str, float]:
    """`control_update_us_<controller>` for each; the client context and the router must be up."""
    costs = {"joint_trajectory_controller": _jtc(), **_sensors(),
             "joint_group_position_controller": _joint_group(), **_drives(), "tricycle_controller": _tricycle(),
             "parallel_gripper_action_controller": _gripper()}
    assert all(math.isfinite(v) for v in costs.values())
    return {f"control_update_us_{k}": v for k, v in costs.items()}


def run() -> dict:
    """Standalone: a router and a client context of its own (`python -m bench control_controllers`)."""
    import os
    import signal
    import subprocess
    import sys

    from bench.ports import free_port, wait_port
    from diffctl.bus.session import close_session
    from diffctl.client import runtime
    from diffctl.client.signals import SignalHandlerOptions

    port = free_port()
    endpoint = f"tcp/127.0.0.1:{port}"
    old = os.environ.get("DIFFCTL_ROUTER")
    os.environ["DIFFCTL_ROUTER"] = endpoint
    router = subprocess.Popen([sys.executable, "-m", "diffctl", "router", "--listen", endpoint],
                              start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        wait_port(port)
        runtime.init(args=["bench_controllers"], signal_handler_options=SignalHandlerOptions.NO)
        return measure()
    finally:
        runtime.try_shutdown()
        close_session()
        os.killpg(router.pid, signal.SIGINT)
        try:
            router.wait(5)
        except subprocess.TimeoutExpired:
            os.killpg(router.pid, signal.SIGKILL)
        if old is None:
            os.environ.pop("DIFFCTL_ROUTER", None)
        else:
            os.environ["DIFFCTL_ROUTER"] = old


if __name__ == "__main__":
    import json

    print(json.dumps(run(), indent=2))
