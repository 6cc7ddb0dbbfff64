"""The game pad loop on a real router, fed scripted evdev frames: enable, autorepeat, turbo, one zero."""

from __future__ import annotations

import queue
import threading
import time

import pytest

from diffctl.client.context import Context
from diffctl.client.node import Node as ClientNode
from diffctl.teleop.joy import run_joy
from diffctl.teleop.joy_config import JoyParams
from diffctl.teleop.joy_mapping import AxisRange
from diffctl.teleop.linux_input import AXES, BUTTONS, EV_ABS, EV_KEY, EV_SYN, SYN_REPORT
from diffctl.teleop.twist_command import TwistCommand
from tests.probe import Probe

STICK = AxisRange(-32768, 32767)


class ScriptedPad:
    """A JoySource whose frames the test pushes, as the kernel would deliver them."""

    def __init__(self) -> None:
        self.axis_ranges = {AXES["LEFTX"]: STICK, AXES["LEFTY"]: STICK}
        self.frames: queue.Queue[list[tuple[int, int, int]]] = queue.Queue()

    def initial_events(self) -> list[tuple[int, int, int]]:
        return []

    def read(self, timeout_s: float | None) -> list[tuple[int, int, int]]:
        try:
            return self.frames.get(timeout=timeout_s)
        except queue.Empty:
            return []

    def push(self, *events: tuple[int, int, int]) -> None:
        self.frames.put([*events, (EV_SYN, SYN_REPORT, 0)])


def test_enable_turbo_autorepeat_and_single_zero(router: str) -> None:
    topic = "/diffbot_base_controller/cmd_vel"
    probe = Probe("joy_probe")
    got: list[tuple[float, float, float, str]] = []
    probe.create_subscription(
        topic,
        "geometry_msgs/msg/TwistStamped",
        lambda m: got.append((time.monotonic(), m.twist.linear.x, m.twist.angular.z, m.header.frame_id)),
    )
    context = Context()
    context.init(args=[])
    teleop_node = ClientNode("teleop_twist_joy_node", context=context)
    params = JoyParams.from_params({"autorepeat_rate": 20.0, "publish_stamped_twist": True}, "xbox")
    command = TwistCommand(teleop_node, topic, stamped=True, frame_id=params.frame)
    pad = ScriptedPad()
    stop = threading.Event()
    deadline = time.monotonic() + 5
    while not command.pub.get_subscription_count() and time.monotonic() < deadline:
        time.sleep(0.02)
    loop = threading.Thread(target=run_joy, args=(pad, params, command, stop))
    before_start = len(got)
    loop.start()

    def settle(seconds: float) -> list[tuple[float, float, float, str]]:
        start = len(got)
        time.sleep(seconds)
        return got[start:]

    try:
        time.sleep(0.3)
        first = got[before_start:]
        assert [(x, z) for _, x, z, _ in first] == [(0.0, 0.0)], "not enabled: exactly one zero at start"
        assert first[0][3] == "teleop_twist_joy"

        pad.push((EV_ABS, AXES["LEFTY"], -32768), (EV_ABS, AXES["LEFTX"], 0))
        assert settle(0.3) == [], "stick without enable button moves nothing"

        pad.push((EV_KEY, BUTTONS["LB"], 1))
        held = settle(0.5)
        assert len(held) >= 6, "autorepeat_rate 20 Hz keeps publishing while enabled"
        assert all(x == pytest.approx(0.7) and z == pytest.approx(0.0, abs=1e-4) for _, x, z, _ in held)

        pad.push((EV_KEY, BUTTONS["RB"], 1), (EV_ABS, AXES["LEFTX"], -32768))
        turbo = settle(0.3)
        assert turbo and turbo[-1][1] == pytest.approx(1.5) and turbo[-1][2] == pytest.approx(1.0)

        pad.push((EV_KEY, BUTTONS["RB"], 0), (EV_KEY, BUTTONS["LB"], 0))
        released = settle(0.5)
        assert [(x, z) for _, x, z, _ in released] == [(0.0, 0.0)], "release sends one zero, then silence"
    finally:
        stop.set()
        loop.join(5)
        teleop_node.destroy_node()
        context.try_shutdown()
        probe.close()
    assert not loop.is_alive()
