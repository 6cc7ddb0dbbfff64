"""joy_node's and joy_linux_node's message state against what their READMEs and sources say (joy 3.3.0): the
deadzone semantics ("0.1 means the joystick has to move 10% of the way to the edge"), forward/left positive,
sticky buttons toggling on press, hats as the last axes (two per hat, left/up positive), buttons published at
once, axis events coalesced, autorepeat at its rate and off at 0."""

from __future__ import annotations

import pytest

from diffctl.joy.joy_state import JoyParams, JoyState, Slot, axis_value, sdl_layout
from diffctl.joy.linux_joystick import JS_EVENT_AXIS, JS_EVENT_BUTTON, JS_EVENT_INIT, JsEvent
from diffctl.joy_linux import joy_state as linux

MS = 1_000_000


def test_axis_scaling_deadzone_and_sign() -> None:
    assert axis_value(32767, 0.05) == -1.0 and axis_value(-32768, 0.05) == 1.0  # SDL's -32768 is clamped
    assert axis_value(3276, 0.1) == 0.0 and axis_value(-3276, 0.1) == 0.0  # inside 10 %
    assert axis_value(3277 + 14745, 0.1) == pytest.approx(-0.5, abs=1e-4)  # half-way past the deadzone
    assert axis_value(16384, 0.0) == pytest.approx(-0.50002, abs=1e-5)
    assert axis_value(20000, 1.0) == 0.0  # a deadzone of the whole range
    assert isinstance(axis_value(1000, 0.05), float)


def test_hats_follow_the_plain_axes_as_sdl_orders_them() -> None:
    # An Xbox 360 pad: X Y Z RX RY RZ HAT0X HAT0Y; a joystick with its hat before its throttle's code.
    assert sdl_layout((0, 1, 2, 3, 4, 5, 0x10, 0x11)).axes == 8
    layout = sdl_layout((0, 1, 0x10, 0x11, 0x28))
    assert layout.axes == 5
    assert layout.slots == (Slot(0), Slot(1), Slot(3, 0, False), Slot(4, 0, True), Slot(2))
    assert sdl_layout((0x12,)).slots == (Slot(0, 0, False),)  # a lone HAT1X is hat 0 here: SDL counts hats present


def test_hat_directions_and_centring() -> None:
    state = JoyState(JoyParams(), 0)
    state.attach(4, 0)
    x, y = Slot(2, 0, False), Slot(3, 0, True)
    assert state.hat(x, -1) and state.axes[2:] == [1.0, 0.0]  # left
    assert state.hat(y, 1) and state.axes[2:] == [1.0, -1.0]  # left + down
    assert state.hat(x, 0) and state.axes[2:] == [1.0, -1.0]  # still down: joy_node leaves left/right as it was
    assert state.hat(y, 0) and state.axes[2:] == [0.0, 0.0]  # centred: both cleared
    assert state.hat(x, 1) and state.axes[2] == -1.0  # right


def test_buttons_publish_at_once_and_stick_when_sticky() -> None:
    state = JoyState(JoyParams(), 0)
    state.attach(0, 2)
    assert state.button(1, True) and state.buttons == [0, 1]
    assert state.button(1, False) and state.buttons == [0, 0]
    sticky = JoyState(JoyParams(sticky_buttons=True), 0)
    sticky.attach(0, 1)
    assert sticky.button(0, True) and sticky.buttons == [1]
    assert not sticky.button(0, False) and sticky.buttons == [1]  # release: nothing
    assert sticky.button(0, True) and sticky.buttons == [0]
    assert not sticky.button(5, True) and sticky.warnings == ["Saw button too large for this device, ignoring"]


def test_axis_changes_coalesce_and_autorepeat_keeps_its_own_clock() -> None:
    state = JoyState(JoyParams(autorepeat_rate_hz=20.0, coalesce_interval_ms=1), 0)
    state.attach(2, 0)
    assert state.wait_ms() == 50
    assert not state.axis(0, 20000, 1 * MS)  # marked, not sent
    assert state.wait_ms() == 1
    assert not state.axis(0, 20000, 1 * MS)  # no change
    assert state.settle(False, 2 * MS)  # the next step sends it
    assert not state.settle(False, 30 * MS)
    assert state.settle(False, 52 * MS)  # 50 ms after the last repeat
    assert not state.settle(False, 101 * MS) and state.settle(False, 102 * MS)
    off = JoyState(JoyParams(autorepeat_rate_hz=0.0, coalesce_interval_ms=0), 0)
    off.attach(1, 0)
    assert off.wait_ms() == 200 and not off.settle(False, 10_000 * MS)
    assert off.axis(0, -30000, 5 * MS)  # no coalescing: sent with the event


def test_a_device_without_counts_grows_with_its_events() -> None:
    state = JoyState(JoyParams(), 0)
    state.attach(None, None)
    state.initial_button(3)
    state.initial_axis(1, -32767)
    assert state.buttons == [0, 0, 0, 0] and state.axes == [0.0, 1.0]


def js(kind: int, number: int, value: int, init: bool = False) -> JsEvent:
    return JsEvent(0, value, kind | (JS_EVENT_INIT if init else 0), number)


def test_joy_linux_publishes_buttons_now_and_coalesces_axes() -> None:
    params, warnings = linux.corrected(0.05, 20.0, 0.001, False, False)
    assert not warnings
    state = linux.LinuxJoyState(params, 0)
    assert state.wait_s(0) == 1.0  # nothing yet: a one-second wait
    assert not state.step(js(JS_EVENT_BUTTON, 0, 0, init=True), 0)  # initial state: waits to gather
    assert not state.step(js(JS_EVENT_AXIS, 1, 20000, init=True), 0)
    assert state.axes == [0.0, 0.0]  # initial axis values are not taken (default_trig_val false)
    assert state.deadline_ns == 1 * MS  # coalescing timer
    assert state.step(None, 1 * MS)  # runs out: publish
    assert state.deadline_ns == 51 * MS  # then autorepeat
    assert state.step(js(JS_EVENT_BUTTON, 2, 1), 10 * MS) and state.buttons == [0, 0, 1]
    assert not state.step(js(JS_EVENT_AXIS, 0, -32767), 12 * MS) and state.axes[0] == pytest.approx(1.0)
    assert not state.step(js(JS_EVENT_AXIS, 0, -16000), 12 * MS + 500_000)  # inside the same interval
    assert state.deadline_ns == 13 * MS
    assert state.step(None, 13 * MS) and state.axes[0] == pytest.approx((16000 - 1638.35) / (0.95 * 32767))


def test_joy_linux_parameter_corrections() -> None:
    params, warnings = linux.corrected(3276.7, -1.0, -0.5, True, True)
    assert params.deadzone == pytest.approx(0.1) and params.autorepeat_rate_hz == 0.0
    assert params.coalesce_interval_s == 0.0
    # checked as given first (-1 Hz > 1 / -0.5 s), then each correction
    assert [w.split(":")[0] for w in warnings] == ["joy_linux_node", "joy_linux_node", "joy_node", "joy_node"]
    assert linux.corrected(0.95, 0, 0.001, False, False)[0].deadzone == 0.9
    state = linux.LinuxJoyState(params, 0)
    state.step(js(JS_EVENT_AXIS, 0, 32767, init=True), 0)
    assert state.axes == [-1.0]  # default_trig_val: the initial value is taken
    assert state.step(None, 0) and not state.step(None, 10**9)  # no autorepeat
    assert state.step(js(JS_EVENT_BUTTON, 0, 1), 0) and state.buttons == [1]
    assert state.step(js(JS_EVENT_BUTTON, 0, 0), 0) and state.buttons == [1]  # sticky: a release keeps it
