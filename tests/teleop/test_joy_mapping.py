"""joy + teleop_twist_joy logic on synthetic evdev events: deadzone, enable, turbo, zero on release."""

from __future__ import annotations

import pytest

from diffctl.errors import ParameterError
from diffctl.teleop.joy_config import JoyParams
from diffctl.teleop.joy_mapping import ZERO, AxisRange, JoyState, JoyTeleop, normalize_axis
from diffctl.teleop.linux_input import AXES, BUTTONS, EV_ABS, EV_KEY

STICK = AxisRange(-32768, 32767)
TRIGGER = AxisRange(0, 255)
RANGES = {AXES["LEFTX"]: STICK, AXES["LEFTY"]: STICK, AXES["TRIGGERLEFT"]: TRIGGER}


def stick(name: str, value: int) -> tuple[int, int, int]:
    return (EV_ABS, AXES[name], value)


def button(name: str, down: bool) -> tuple[int, int, int]:
    return (EV_KEY, BUTTONS[name], int(down))


def test_normalize_axis_follows_joy_convention_and_deadzone() -> None:
    assert normalize_axis(-32768, STICK, 0.0) == 1.0  # stick fully up / left → +1
    assert normalize_axis(32767, STICK, 0.0) == -1.0
    assert normalize_axis(0, STICK, 0.0) == pytest.approx(0.0, abs=1e-4)
    assert normalize_axis(-9000, STICK, 0.3) == 0.0  # inside the deadzone
    # Outside it, the remaining travel is rescaled so the edge of the deadzone is 0 and full travel is 1.
    assert normalize_axis(-int(0.65 * 32768), STICK, 0.3) == pytest.approx(0.5, abs=1e-3)
    assert normalize_axis(0, TRIGGER, 0.0) == 1.0  # a released trigger reads +1, as in joy


def drive(params: JoyParams, *events: tuple[int, int, int]) -> tuple[JoyState, JoyTeleop]:
    state = JoyState(RANGES, params.deadzone)
    state.apply_all(events)
    return state, JoyTeleop(params)


def test_xbox_enable_turbo_and_one_zero_on_release() -> None:
    p = JoyParams.from_params({}, "xbox")
    state, t = drive(p, stick("LEFTY", -32768), stick("LEFTX", 32767))
    # Not enabled: one zero command, then silence.
    assert t.update(state) == ZERO
    assert t.update(state) is None
    state.apply(*button("LB", True))
    cmd = t.update(state)
    assert cmd.linear_m_s[0] == pytest.approx(0.7) and cmd.angular_rad_s[2] == pytest.approx(-0.4)
    state.apply(*button("RB", True))
    turbo = t.update(state)
    assert turbo.linear_m_s[0] == pytest.approx(1.5) and turbo.angular_rad_s[2] == pytest.approx(-1.0)
    state.apply(*button("RB", False))
    state.apply(*button("LB", False))
    assert t.update(state) == ZERO
    assert t.update(state) is None


def test_deadzone_keeps_a_resting_stick_still() -> None:
    p = JoyParams.from_params({"deadzone": 0.3}, "ps3")
    state, t = drive(p, button("L2", True), stick("LEFTY", -6000), stick("LEFTX", 5000))
    assert t.update(state).is_zero


def test_require_enable_button_false_and_inverted_reverse() -> None:
    p = JoyParams.from_params({"require_enable_button": False, "inverted_reverse": True}, "atk3")
    state, t = drive(p, stick("LEFTY", 32767), stick("LEFTX", -32768))
    cmd = t.update(state)
    # Stick back and left: left is +yaw, but inverted_reverse flips the turn while reversing, as upstream.
    assert cmd.linear_m_s[0] == pytest.approx(-0.7, abs=1e-4) and cmd.angular_rad_s[2] == pytest.approx(-0.4)
    plain = JoyTeleop(JoyParams.from_params({"require_enable_button": False}, "atk3")).update(state)
    assert plain.angular_rad_s[2] == pytest.approx(0.4)


def test_numeric_indices_are_sdl_order_and_minus_one_is_none() -> None:
    p = JoyParams.from_params(
        {"enable_button": 9, "enable_turbo_button": -1, "axis_linear.x": 1, "axis_angular.yaw": 0}, "xbox"
    )
    assert (p.enable_button, p.enable_turbo_button, p.axis_linear["x"]) == ("LB", None, "LEFTY")


@pytest.mark.parametrize(
    ("params", "preset", "expected"),
    [
        ({}, "xbax", r"joy_config: 'xbax' unknown \(did you mean 'xbox'\?\); valid: xbox, ps3, atk3"),
        ({"enable_button": "LBB"}, "xbox", r"enable_button: button 'LBB' unknown \(did you mean 'LB'"),
        ({"enable_button": 42}, "xbox", r"enable_button: button index 42 invalid; valid: -1 \(none\) or 0..14"),
        ({"axis_linear.w": 1}, "xbox", r"axis_linear.w: unknown field 'w'; valid: x, y, z"),
        ({"scale_linear.x": float("inf")}, "xbox", r"scale_linear.x: inf invalid"),
        ({"deadzone": 1.5}, "xbox", r"deadzone: 1.5 out of range"),
        ({"publish_stamped_twist": "yes"}, "xbox", r"publish_stamped_twist: 'yes' invalid; valid: true, false"),
    ],
)
def test_bad_parameters_name_the_parameter_and_valid_values(params: dict, preset: str, expected: str) -> None:
    with pytest.raises(ParameterError, match=expected):
        JoyParams.from_params(params, preset)
