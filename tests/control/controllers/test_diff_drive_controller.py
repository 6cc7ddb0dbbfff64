"""DiffDriveController driven directly (a real client node, real interface handles): odometry, timeout braking,
stale and bad commands, deactivation, feedback modes, several wheels per side, publishing and the cost of
update()."""

from __future__ import annotations

import functools
import math
import time

import pytest
from controller_harness import NS, activate, configure, hand_interfaces, make_controller, update

from diffctl.control.controller_interface import ReturnType
from diffctl.control.controllers.diff_drive import DiffDriveController
from diffctl.control.lifecycle import State
from diffctl.control.realtime_publisher import PublishingThread, RealtimePublisher

pytestmark = pytest.mark.usefixtures("client_bus")

NAME = "diffbot_base_controller"
CMD = f"/{NAME}/cmd_vel"
ODOM = f"/{NAME}/odom"
BASE = {
    "left_wheel_names": ["left_wheel"],
    "right_wheel_names": ["right_wheel"],
    "wheel_separation": 0.3,
    "wheel_radius": 0.04,
}


class Drive:
    """An active controller plus a tiny 'hardware' that integrates the wheel commands (mock calculate_dynamics)."""

    def __init__(self, rate_hz: int = 100, namespace: str = "/", **params):
        self.c = make_controller(DiffDriveController, NAME, {**BASE, **params}, namespace=namespace,
                                 update_rate=rate_hz)
        self.node = self.c.probe
        configure(self.c)
        self.cmd, self.state = hand_interfaces(self.c)
        activate(self.c)
        self.period_s = 1.0 / rate_hz
        self.t_ns = self.node.time_ns
        self.positions = {w: 0.0 for w in (*self.c.params.left_wheel_names, *self.c.params.right_wheel_names)}

    def send(self, v: float, w: float, age_s: float = 0.0, stamp_ns: int | None = None) -> None:
        stamp = self.node.time_ns - round(age_s * NS) if stamp_ns is None else stamp_ns
        sec, nanosec = divmod(stamp, NS)
        self.node.deliver(
            self.node.resolve("~/cmd_vel"),
            {"header": {"stamp": {"sec": sec, "nanosec": nanosec}}, "twist": {"linear": {"x": v}, "angular": {"z": w}}},
        )

    def step(self) -> ReturnType:
        result = update(self.c, self.t_ns, self.period_s)
        for wheel in self.positions:  # the hardware moves the wheels during the next period
            cmd = self.cmd[f"{wheel}/velocity"].value
            if math.isfinite(cmd):
                self.positions[wheel] += cmd * self.period_s
                for iface, value in (("position", self.positions[wheel]), ("velocity", cmd)):
                    if f"{wheel}/{iface}" in self.state:
                        self.state[f"{wheel}/{iface}"].value = value
        self.t_ns += round(self.period_s * NS)
        self.node.time_ns = self.t_ns
        return result

    def run(self, seconds: float, v: float | None = None, w: float = 0.0, resend_s: float = 0.1) -> None:
        steps = round(seconds / self.period_s)
        every = max(1, round(resend_s / self.period_s))
        for k in range(steps):
            if v is not None and k % every == 0:
                self.send(v, w)
            assert self.step() is ReturnType.OK

    def wheel(self, name: str) -> float:
        return self.cmd[f"{name}/velocity"].value

    @property
    def odom(self):
        return self.c.odometry


def test_interfaces_claimed_per_feedback_mode():
    def names(**p):
        c = make_controller(DiffDriveController, NAME, {**BASE, **p})
        return c.command_interface_configuration().names, c.state_interface_configuration()

    cmd, st = names()
    assert cmd == ["left_wheel/velocity", "right_wheel/velocity"]
    assert st.names == ["left_wheel/position", "right_wheel/position"]
    assert names(position_feedback=False)[1].names == ["left_wheel/velocity", "right_wheel/velocity"]
    assert names(open_loop=True)[1].type == "none"
    cmd, _ = names(left_wheel_names=["l1", "l2"], right_wheel_names=["r1", "r2"])
    assert cmd == ["l1/velocity", "l2/velocity", "r1/velocity", "r2/velocity"]


@pytest.mark.parametrize("mode", ["open_loop", "position", "velocity"])
def test_odom_after_one_second_at_0_2(mode):
    params = {"open_loop": mode == "open_loop", "position_feedback": mode == "position"}
    d = Drive(**params)
    d.run(1.0, v=0.2)
    x = d.node.sent(ODOM)[-1]["pose"]["pose"]["position"]["x"]
    if mode == "open_loop":
        assert x == pytest.approx(0.2, abs=1e-9)
    else:  # feedback lags the command by one tick (0.002 m at 100 Hz)
        assert x == pytest.approx(0.2, rel=0.02)
    assert d.wheel("left_wheel") == pytest.approx(5.0) and d.wheel("right_wheel") == pytest.approx(5.0)
    last = d.node.sent(ODOM)[-1]
    assert last["twist"]["twist"]["linear"]["x"] == pytest.approx(0.2)
    assert (last["header"]["frame_id"], last["child_frame_id"]) == ("odom", "base_link")


def test_arc_odometry_and_message_content():
    d = Drive(
        open_loop=True,
        pose_covariance_diagonal=[0.001, 0.001, 0.0, 0.0, 0.0, 0.01],
        base_frame_id="base_footprint",
    )
    d.run(1.0, v=0.2, w=0.5)
    msg = d.node.sent(ODOM)[-1]
    pose = msg["pose"]["pose"]
    assert (pose["position"]["x"], pose["position"]["y"]) == pytest.approx(
        (0.4 * math.sin(0.5), 0.4 * (1 - math.cos(0.5))), abs=1e-9
    )
    assert (pose["orientation"]["z"], pose["orientation"]["w"]) == pytest.approx((math.sin(0.25), math.cos(0.25)))
    assert msg["pose"]["covariance"][0] == 0.001 and msg["pose"]["covariance"][35] == 0.01
    assert msg["twist"]["twist"]["angular"]["z"] == pytest.approx(0.5)
    tf = d.node.sent("/tf")[-1]["transforms"][0]
    assert (tf["header"]["frame_id"], tf["child_frame_id"]) == ("odom", "base_footprint")
    assert tf["transform"]["translation"]["x"] == pytest.approx(pose["position"]["x"])
    assert tf["header"]["stamp"] == msg["header"]["stamp"]
    assert d.wheel("left_wheel") == pytest.approx((0.2 - 0.5 * 0.15) / 0.04)


def test_publish_rate_frame_prefix_and_limited_velocity_out():
    d = Drive(rate_hz=100, namespace="/robot1", open_loop=True, publish_limited_velocity=True, publish_rate=20.0)
    d.run(1.0, v=0.2)
    assert len(d.node.sent("/robot1/diffbot_base_controller/odom")) == pytest.approx(20, abs=1)
    assert len(d.node.sent("/tf")) == len(d.node.sent("/robot1/diffbot_base_controller/odom"))
    assert len(d.node.sent("/robot1/diffbot_base_controller/cmd_vel_out")) == 100
    tf = d.node.sent("/tf")[-1]["transforms"][0]
    assert (tf["header"]["frame_id"], tf["child_frame_id"]) == ("robot1/odom", "robot1/base_link")


def test_enable_odom_tf_false_publishes_no_tf():
    d = Drive(open_loop=True, enable_odom_tf=False)
    d.run(0.2, v=0.2)
    assert d.node.sent(ODOM) and "/tf" not in d.node.publishers


def test_nothing_written_before_the_first_command_then_timeout_brakes_to_zero():
    d = Drive(open_loop=True)
    d.cmd["left_wheel/velocity"].value = math.nan  # marks "never written"
    d.run(0.3)
    assert math.isnan(d.wheel("left_wheel")) and d.node.sent(ODOM) == []
    d.run(0.3)  # past cmd_vel_timeout after activation: the reference brakes (writes zero) and publishes
    assert d.wheel("left_wheel") == 0.0 and d.node.sent(ODOM)
    assert "timed out" not in d.node.log.text()  # no real command expired


def test_cmd_vel_timeout_brakes_through_the_limiter():
    d = Drive(open_loop=True, **{"linear.x.max_acceleration": 1.0})
    d.run(1.0, v=0.2)
    assert d.wheel("left_wheel") == pytest.approx(5.0)
    last_cmd_t = d.t_ns - round(0.1 * NS)  # the last send was at k = 90
    d.run(0.4)  # within 0.5 s of the last command; the next tick is exactly at the timeout
    assert d.wheel("left_wheel") == pytest.approx(5.0)
    braking = []
    while d.t_ns <= last_cmd_t + round(0.8 * NS):
        d.step()
        braking.append(d.wheel("left_wheel") * 0.04)
    assert braking[0] == pytest.approx(0.2)  # the tick at exactly the timeout still drives
    decel = [round(b, 6) for b in braking[1:23]]
    assert decel[:3] == pytest.approx([0.19, 0.18, 0.17])  # 1 m/s² at 100 Hz
    assert decel[-3:] == [0.0, 0.0, 0.0]
    assert d.node.log.text("WARN").count("Velocity command timed out. Braking.") == 1


def test_cmd_vel_timeout_zero_keeps_the_last_command():
    d = Drive(open_loop=True, cmd_vel_timeout=0.0)
    d.run(0.1, v=0.2)
    d.send(0.2, 0.0, age_s=100.0)  # an old stamp is fine when the timeout is off
    d.run(3.0)
    assert d.wheel("left_wheel") == pytest.approx(5.0)
    assert "Ignoring" not in d.node.log.text()


def test_stale_stamps_are_ignored_with_the_reason_and_future_stamps_accepted():
    d = Drive(open_loop=True)
    d.run(0.5, v=0.1)
    d.send(0.2, 0.0, age_s=0.6)
    d.run(0.05)
    assert d.wheel("left_wheel") == pytest.approx(2.5)
    warn = d.node.log.text("WARN")
    assert "older than the current time by 0.6" in warn and "exceeds the allowed timeout (0.5)" in warn
    # Jazzy keeps a command stamped ahead of its clock; it times out cmd_vel_timeout after that stamp.
    d.send(0.3, 0.0, age_s=-3.0)
    d.run(3.3)
    assert d.wheel("left_wheel") == pytest.approx(7.5)
    d.run(0.3)
    assert d.wheel("left_wheel") == 0.0
    assert "Braking" in d.node.log.text("WARN")


def test_zero_stamp_means_now():
    d = Drive(open_loop=True)
    d.run(1.0)  # well past the timeout since activation
    d.send(0.2, 0.0, stamp_ns=0)
    d.send(0.2, 0.0, stamp_ns=0)
    d.run(0.3)
    assert d.wheel("left_wheel") == pytest.approx(5.0)
    assert d.node.log.text("WARN").count("zero timestamp") == 1


@pytest.mark.parametrize(("v", "w"), [(math.nan, 0.0), (0.2, math.inf), (-math.inf, math.nan)])
def test_non_finite_commands_keep_the_previous_reference_with_a_throttled_warning(v, w):
    d = Drive(open_loop=True)
    d.run(0.3, v=0.1)
    before = (d.wheel("left_wheel"), d.wheel("right_wheel"))
    d.run(1.0, v=v, w=w, resend_s=0.01)  # 100 bad commands, each one fresh: the reference stays, no timeout
    assert (d.wheel("left_wheel"), d.wheel("right_wheel")) == pytest.approx(before)
    warnings = [t for lv, t in d.node.log.lines if lv == "WARN" and "Not updating reference interfaces" in t]
    assert 1 <= len(warnings) < 10  # throttled
    assert "Braking" not in d.node.log.text()


@pytest.mark.parametrize(("v", "w"), [(1e6, 0.0), (0.0, -500.0)])
def test_absurd_commands_change_nothing(v, w):
    d = Drive(open_loop=True)
    d.run(0.3, v=0.1)
    before = (d.wheel("left_wheel"), d.wheel("right_wheel"))
    d.send(v, w)
    d.run(0.1)
    assert (d.wheel("left_wheel"), d.wheel("right_wheel")) == pytest.approx(before)
    assert "Ignoring a velocity command" in d.node.log.text("WARN")


def test_deactivate_writes_zero_and_stops_accepting_commands():
    d = Drive(open_loop=True)
    d.run(0.5, v=0.2)
    d.c.on_deactivate(State.ACTIVE)
    assert d.cmd["left_wheel/velocity"].value == 0.0 and d.cmd["right_wheel/velocity"].value == 0.0
    d.send(0.2, 0.0)
    assert "subscriber is inactive" in d.node.log.text("WARN")
    x = d.odom.x_m
    d.cmd, d.state = hand_interfaces(d.c, {"left_wheel/velocity": 0.0})
    activate(d.c)  # reactivated: no command until a new one arrives; odometry was kept
    d.run(0.2)
    assert d.wheel("left_wheel") == 0.0 and d.odom.x_m == pytest.approx(x)


def test_nan_feedback_returns_error_and_error_resets_odometry():
    d = Drive()
    d.run(0.5, v=0.2)
    assert d.odom.x_m > 0.05
    d.state["right_wheel/position"].value = math.nan
    d.send(0.2, 0.0)
    assert update(d.c, d.t_ns, d.period_s) is ReturnType.ERROR
    assert "Either the left or right wheel position is invalid for index [0]" in d.node.log.text("ERROR")
    d.c.on_error(State.ACTIVE)
    d.c.on_deactivate(State.ACTIVE)
    assert d.odom.x_m == 0.0 and d.wheel("left_wheel") == 0.0


def test_several_wheels_per_side_with_multipliers_and_mean_feedback():
    d = Drive(
        position_feedback=False,
        left_wheel_names=["fl", "rl"],
        right_wheel_names=["fr", "rr"],
        left_wheel_radius_multiplier=0.5,
        wheel_separation_multiplier=2.0,
    )
    d.run(0.5, v=0.2, w=0.5)
    left = (0.2 - 0.5 * 0.6 / 2) / 0.02
    right = (0.2 + 0.5 * 0.6 / 2) / 0.04
    assert [d.wheel(n) for n in ("fl", "rl", "fr", "rr")] == pytest.approx([left, left, right, right])
    # one slipping rear-left wheel: odometry uses the mean of the side
    d.state["rl/velocity"].value = 0.0
    update(d.c, d.t_ns, d.period_s)
    assert d.odom.linear_mps < 0.2


def test_cleanup_closes_endpoints_and_reconfigure_works():
    d = Drive(open_loop=True)
    d.c.on_deactivate(State.ACTIVE)
    d.c.on_cleanup(State.INACTIVE)
    assert not d.node.publishers and CMD not in d.node.subscriptions
    configure(d.c)
    assert CMD in d.node.subscriptions and f"/{NAME}/odom" in d.node.publishers


def test_update_cost_per_tick():
    """update() on the real message path (the template packing included), position feedback, publishing at
    50 Hz."""
    d = Drive(publish_limited_velocity=True)
    thread = PublishingThread()  # the real one: samples queued here, put on the bus by its own thread
    for rp in d.c._endpoints._items:
        if isinstance(rp, RealtimePublisher):
            rp._thread, rp.publish_values = thread, functools.partial(thread.submit, rp.publisher)
    d.send(0.2, 0.1)
    costs = []
    for _ in range(600):
        t0 = time.perf_counter()
        update(d.c, d.t_ns, d.period_s)
        costs.append(time.perf_counter() - t0)
        d.t_ns += round(d.period_s * NS)
    costs.sort()
    median_us = costs[len(costs) // 2] * 1e6
    print(f"diff_drive update(): median {median_us:.1f} µs, p99 {costs[int(len(costs) * 0.99)] * 1e6:.1f} µs")
    assert median_us < 100.0
