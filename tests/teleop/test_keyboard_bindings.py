"""teleop_twist_keyboard's bindings as a pure state machine."""

from __future__ import annotations

import pytest

from diffctl.errors import ParameterError
from diffctl.teleop.keyboard_bindings import KeyboardParams, KeyboardTeleop, split_keys


@pytest.mark.parametrize(
    ("key", "velocity"),
    [
        ("i", (0.5, 0.0, 0.0, 0.0)),
        ("u", (0.5, 0.0, 0.0, 1.0)),
        ("o", (0.5, 0.0, 0.0, -1.0)),
        ("j", (0.0, 0.0, 0.0, 1.0)),
        ("l", (0.0, 0.0, 0.0, -1.0)),
        (",", (-0.5, 0.0, 0.0, 0.0)),
        ("m", (-0.5, 0.0, 0.0, -1.0)),
        (".", (-0.5, 0.0, 0.0, 1.0)),
        ("J", (0.0, 0.5, 0.0, 0.0)),
        ("t", (0.0, 0.0, 0.5, 0.0)),
        ("UP", (0.5, 0.0, 0.0, 0.0)),
        ("k", (0.0, 0.0, 0.0, 0.0)),
        ("?", (0.0, 0.0, 0.0, 0.0)),
    ],
)
def test_move_keys(key: str, velocity: tuple[float, ...]) -> None:
    t = KeyboardTeleop(KeyboardParams())
    t.press("i")
    assert t.press(key)
    assert t.velocity() == pytest.approx(velocity)


def test_speed_keys_scale_and_cap() -> None:
    t = KeyboardTeleop(KeyboardParams(speed_m_s=1.0, turn_rad_s=1.0, speed_limit_m_s=1.5, turn_limit_rad_s=2.0))
    t.press("q")
    assert (t.speed_m_s, t.turn_rad_s) == pytest.approx((1.1, 1.1))
    t.press("x")
    assert (t.speed_m_s, t.turn_rad_s) == pytest.approx((0.99, 1.1))
    t.press("c")
    assert t.turn_rad_s == pytest.approx(0.99)
    for _ in range(50):
        t.press("q")
    assert (t.speed_m_s, t.turn_rad_s) == (1.5, 2.0)
    assert t.press("i") and t.velocity()[0] == 1.5


def test_quit_keys_and_arrow_sequences() -> None:
    t = KeyboardTeleop(KeyboardParams())
    assert not t.press("\x03") and not t.press("\x04")
    assert split_keys("i\x1b[A\x1b[Dq,") == ["i", "UP", "LEFT", "q", ","]


@pytest.mark.parametrize("bad", [{"speed_m_s": float("nan")}, {"turn_rad_s": -1.0}, {"speed_m_s": 9.0}])
def test_bad_parameters(bad: dict) -> None:
    with pytest.raises(ParameterError):
        KeyboardParams(**bad)
