"""Speed limiter on hand-computed cases: velocity clamp, acceleration (asymmetric, reverse), jerk, NaN limits."""

from __future__ import annotations

import math

import pytest

from diffctl.control.math.speed_limiter import LimitError, SpeedLimiter, SpeedLimits

NAN = math.nan
DT = 0.1


def run(limiter: SpeedLimiter, target: float, steps: int, v0: float = 0.0, v1: float = 0.0) -> list[float]:
    """Feed `target` for `steps` updates, keeping the two-deep history as the controller does."""
    out = []
    for _ in range(steps):
        v = limiter.limit(target, v0, v1, DT)
        v0, v1 = v, v0
        out.append(v)
    return out


def test_all_nan_limits_pass_everything_through():
    lim = SpeedLimiter(SpeedLimits())
    assert not lim.enabled
    for v in (0.0, 3.5, -1e3, 1e-9):
        assert lim.limit(v, 0.2, -0.7, DT) == v


def test_velocity_clamp_and_min_defaulting_to_minus_max():
    lim = SpeedLimiter(SpeedLimits(max_velocity=1.0))
    assert lim.limit(2.0, 0.0, 0.0, DT) == 1.0
    assert lim.limit(-3.0, 0.0, 0.0, DT) == -1.0
    asym = SpeedLimiter(SpeedLimits(min_velocity=-0.25, max_velocity=1.0))
    assert asym.limit(-3.0, 0.0, 0.0, DT) == -0.25


def test_nan_max_velocity_disables_even_a_given_min():
    lim = SpeedLimiter(SpeedLimits(min_velocity=-0.5))
    assert lim.limit(-3.0, 0.0, 0.0, DT) == -3.0


def test_acceleration_ramp_from_standstill():
    lim = SpeedLimiter(SpeedLimits(max_acceleration=1.0))
    ramp = run(lim, 0.5, 7)
    assert ramp == pytest.approx([0.1, 0.2, 0.3, 0.4, 0.5, 0.5, 0.5])


def test_forward_braking_uses_max_deceleration():
    lim = SpeedLimiter(SpeedLimits(max_acceleration=1.0, max_deceleration=-3.0))
    # v0 = 0.5 forward, target 0: dv clamped to [-0.3, 0.1]
    assert lim.limit(0.0, 0.5, 0.5, DT) == pytest.approx(0.2)
    assert run(lim, 0.0, 3, v0=0.5, v1=0.5) == pytest.approx([0.2, 0.0, 0.0])


def test_reverse_acceleration_and_reverse_deceleration():
    lim = SpeedLimiter(
        SpeedLimits(
            max_acceleration=1.0, max_acceleration_reverse=-2.0, max_deceleration=-3.0, max_deceleration_reverse=4.0
        )
    )
    # standstill: bounds [max_acceleration_reverse, max_acceleration]
    assert lim.limit(-1.0, 0.0, 0.0, DT) == pytest.approx(-0.2)
    assert lim.limit(1.0, 0.0, 0.0, DT) == pytest.approx(0.1)
    # moving in reverse: speeding up backwards is bounded by -2, braking (towards 0) by +4
    assert lim.limit(-1.0, -0.5, -0.5, DT) == pytest.approx(-0.7)
    assert lim.limit(0.0, -0.5, -0.5, DT) == pytest.approx(-0.1)
    assert run(lim, 0.0, 3, v0=-1.0, v1=-1.0) == pytest.approx([-0.6, -0.2, 0.0])


def test_symmetric_defaults_of_the_asymmetric_limits():
    lim = SpeedLimiter(SpeedLimits(max_acceleration=2.0))
    # max_acceleration_reverse → -2, max_deceleration → -2, max_deceleration_reverse → +2
    assert lim.limit(0.0, 1.0, 1.0, DT) == pytest.approx(0.8)
    assert lim.limit(0.0, -1.0, -1.0, DT) == pytest.approx(-0.8)
    assert lim.limit(-5.0, -1.0, -1.0, DT) == pytest.approx(-1.2)


def test_reverse_deceleration_defaults_to_max_acceleration():
    lim = SpeedLimiter(SpeedLimits(max_acceleration=1.0, max_acceleration_reverse=-3.0))
    assert lim.limit(0.0, -1.0, -1.0, DT) == pytest.approx(-0.9)  # braking in reverse at +1
    assert lim.limit(0.0, 1.0, 1.0, DT) == pytest.approx(0.7)  # forward braking defaults to reverse accel -3


def test_jerk_limited_start_follows_triangular_numbers():
    lim = SpeedLimiter(SpeedLimits(max_jerk=1.0))
    # dt² · jerk = 0.01 per step: v_n = 0.01 · n(n+1)/2
    assert run(lim, 1.0, 5) == pytest.approx([0.01, 0.03, 0.06, 0.10, 0.15])


def test_jerk_not_limited_while_acceleration_shrinks():
    lim = SpeedLimiter(SpeedLimits(max_jerk=1.0))
    # previous step +0.2, this one +0.1: the acceleration falls, which is never jerk-limited
    assert lim.limit(0.6, 0.5, 0.3, DT) == pytest.approx(0.6)


def test_order_jerk_then_acceleration_then_velocity():
    lim = SpeedLimiter(SpeedLimits(max_velocity=1.0, max_acceleration=1.0, max_jerk=100.0))
    # jerk allows +1.0 over dv0 = 0.1, acceleration allows +0.1 → 1.05, velocity clamps to 1.0
    assert lim.limit(3.0, 0.95, 0.85, DT) == pytest.approx(1.0)


def test_nan_command_passes_through_unchanged():
    lim = SpeedLimiter(SpeedLimits(max_velocity=1.0, max_acceleration=1.0, max_jerk=1.0))
    assert math.isnan(lim.limit(NAN, 0.0, 0.0, DT))


def test_zero_dt_allows_no_change_under_acceleration_limits():
    lim = SpeedLimiter(SpeedLimits(max_acceleration=1.0))
    assert lim.limit(1.0, 0.3, 0.3, 0.0) == 0.3


@pytest.mark.parametrize(
    ("limits", "field"),
    [
        (SpeedLimits(min_velocity=2.0, max_velocity=1.0), "min_velocity"),
        (SpeedLimits(max_velocity=-1.0), "min_velocity"),
        (SpeedLimits(max_acceleration=1.0, max_acceleration_reverse=2.0), "max_acceleration_reverse"),
        (SpeedLimits(max_acceleration=1.0, max_deceleration=0.5, max_deceleration_reverse=0.2), "max_deceleration"),
        (SpeedLimits(max_jerk=1.0, min_jerk=3.0), "min_jerk"),
    ],
)
def test_contradicting_limits_name_the_parameter(limits, field):
    with pytest.raises(LimitError) as e:
        SpeedLimiter(limits)
    assert e.value.field == field
