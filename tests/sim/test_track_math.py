"""Pure math of the tracks: what a contact asks of the vehicle under gz-sim's TrackController rule, where the
frictions settle, the belt speeds that keep a belt still on the ground, and `<track_orientation>`."""

from __future__ import annotations

import math

import pytest
from hypothesis import example, given
from hypothesis import strategies as st

from diffctl.description.model import Plugin
from diffctl.errors import DescriptionError
from diffctl.sim.plugins.track_math import (
    ContactPatch,
    asked_rate,
    belt_joint_speeds,
    patch_asks,
    settled_rate,
    track_orientation,
)

UP = (0.0, 0.0, 1.0)  # the ground's normal, into a track standing on it
LEFTWARD = (0.0, 1.0, 0.0)  # a track's y axis, for a track running along +x


def test_a_contact_asks_to_run_along_the_track_or_to_circle_the_centre() -> None:
    # no centre: straight on at the track's speed
    assert asked_rate((0.3, 0.2, 0.0), UP, LEFTWARD, 0.4, None) == (0.4, 1.0)
    # under the track, its surface pushes the vehicle forwards (+x): about a centre 2 m to the left that is a
    # positive (counter-clockwise) turn at speed / distance
    rate, lever = asked_rate((0.0, 0.0, 0.0), UP, LEFTWARD, 0.4, (0.0, 2.0, 0.0))
    assert (rate, lever) == pytest.approx((0.2, 2.0))
    # the centre to the right: the same push is a clockwise turn; the height of the centre does not count
    rate, lever = asked_rate((0.0, 0.0, 0.0), UP, LEFTWARD, 0.4, (0.0, -0.5, 0.7))
    assert (rate, lever) == pytest.approx((-0.8, 0.5))
    # on the centre itself the contact asks nothing
    assert asked_rate((0.0, 0.0, 0.0), UP, LEFTWARD, 0.4, (0.0, 0.0, 0.3)) is None


def test_belt_speeds_cancel_the_vehicles_motion_where_the_belt_is() -> None:
    rate, cx, cy = 0.7, 0.4, -1.5
    along, across, turn = belt_joint_speeds(rate, (cx, cy))
    # the vehicle turning at `rate` about c moves its track frame's origin at rate·z×(origin − c)
    origin_v = (-rate * (0.0 - cy), rate * (0.0 - cx))
    assert (origin_v[0] + along, origin_v[1] + across, rate + turn) == pytest.approx((0.0, 0.0, 0.0))
    assert belt_joint_speeds(0.3, None) == (-0.3, 0.0, 0.0)


@given(
    st.lists(
        st.tuples(st.floats(-3.0, 3.0), st.floats(0.0, 50.0), st.floats(0.05, 3.0)),
        min_size=1,
        max_size=12,
    )
)
@example([(0.0, 5e-324, 1.0)])  # a subnormal load: its pulls times the span underflowed to 0 (found at random)
def test_the_settled_rate_lies_among_the_asks_and_balances_their_pulls(asks) -> None:
    rate = settled_rate(asks)
    assert rate is not None
    assert min(a[0] for a in asks) - 1e-9 <= rate <= max(a[0] for a in asks) + 1e-9
    if sum(load for _, load, _ in asks) > 0.0:
        # the pulls on either side balance (each at most load · lever), unless one side is empty
        def pull(r: float) -> float:
            return sum(load * lever * max(-1.0, min(1.0, lever * (a - r) / 0.02)) for a, load, lever in asks)

        assert pull(rate - 1e-6) >= -1e-6 and pull(rate + 1e-6) <= 1e-6


def test_settling_tends_to_the_weighted_median_and_a_lone_track_sets_the_rate() -> None:
    # Coulomb friction: a side with more moment wins outright; the slip only rounds the balance
    asks = [(0.2, 10.0, 1.0), (0.5, 30.0, 1.0)]
    assert settled_rate(asks) == pytest.approx(0.5, abs=0.02)
    assert settled_rate([(0.3, 5.0, 1.0)]) == pytest.approx(0.3)
    assert settled_rate([]) is None
    # equal moments: between them
    assert settled_rate([(0.2, 10.0, 1.0), (0.4, 10.0, 1.0)]) == pytest.approx(0.3, abs=0.02)


def test_a_patch_shares_its_load_evenly_between_its_points() -> None:
    frame = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (-1.0, 0.0, 0.0), UP)  # the track plane turned 90° about z
    patch = ContactPatch(points_m=((-0.4, 0.2, 0.0), (0.4, 0.2, 0.0), (0.4, 0.3, 0.0)), normal=UP, load_n=90.0)
    assert patch.length_m == pytest.approx(0.8)
    asks = patch_asks(patch, frame, 0.5, None)
    assert asks.tolist() == [[0.5, 30.0, 1.0]] * 3
    # turning in place about the frame's origin: each point asks speed / its distance, clockwise here (the
    # track's forward is the frame's x, world +y, on the world's -x side of the centre)
    turning = patch_asks(patch, frame, 0.5, (1.0, 0.0, 0.5))
    expected = [0.5 / math.hypot(0.4, 0.2), 0.5 / math.hypot(0.4, 0.2), 0.5 / math.hypot(0.4, 0.3)]
    assert [r for r, _, _ in turning] == pytest.approx([-e for e in expected])
    assert [lever for _, _, lever in turning] == pytest.approx([math.hypot(0.4, 0.2)] * 2 + [0.5])


def test_track_orientation_is_roll_pitch_yaw_and_refused_otherwise() -> None:
    def plugin(text: str) -> Plugin:
        return Plugin(
            name="gz::sim::systems::TrackController",
            filename="gz-sim-track-controller-system",
            params=(("link", "l"), ("track_orientation", text)),
        )

    turned = track_orientation(plugin("0 0 1.5707963"))
    assert turned.rotate((1.0, 0.0, 0.0)) == pytest.approx((0.0, 1.0, 0.0), abs=1e-6)
    with pytest.raises(DescriptionError, match=r"track_orientation.*not three finite numbers"):
        track_orientation(plugin("0 0"), "robot.sdf")
