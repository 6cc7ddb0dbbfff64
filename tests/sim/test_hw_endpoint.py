"""Codecs and keys of the sim ↔ controller-manager hardware endpoint."""

from __future__ import annotations

import math

import numpy as np
import pytest

from diffctl.bus import hw_endpoint as hw
from diffctl.errors import MessageError


def test_state_round_trip_is_exact() -> None:
    pos, vel, eff = [0.1, -2.5], [1e-300, math.pi], [0.0, -0.0]
    s = hw.decode_state(hw.encode_state(7, 123_456_789, pos, vel, eff))
    assert (s.tick, s.sim_time_ns) == (7, 123_456_789)
    assert s.position.tolist() == pos and s.velocity.tolist() == vel and s.effort.tolist() == eff


def test_command_nan_means_no_command_and_defaults() -> None:
    c = hw.decode_command(hw.encode_command(3, [1.5, float("nan")]))
    assert c.tick == 3 and c.velocity[0] == 1.5 and math.isnan(c.velocity[1])
    assert np.isnan(c.position).all() and np.isnan(c.effort).all()


@pytest.mark.parametrize("cut", [0, 5, 19, 30])
def test_truncated_samples_raise_message_error(cut: int) -> None:
    with pytest.raises(MessageError, match="truncated"):
        hw.decode_state(hw.encode_state(1, 2, [1.0], [2.0], [3.0])[:cut])
    with pytest.raises(MessageError, match="truncated"):
        hw.decode_command(hw.encode_command(1, [1.0], [2.0], [3.0])[: min(cut, 11)])


def test_keys_and_model_extraction() -> None:
    assert hw.state_key("robot") == "gz/model/robot/ros2_control/state"
    assert hw.model_of_key(hw.endpoint_key("robot")) == "robot"
    assert hw.model_of_key("gz/clock") is None
    with pytest.raises(MessageError):
        hw.command_key("a/b")
    with pytest.raises(MessageError, match="lengths"):
        hw.encode_state(0, 0, [1.0, 2.0], [1.0], [1.0, 2.0])
