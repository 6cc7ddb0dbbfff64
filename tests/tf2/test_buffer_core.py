"""tf2's buffer core: chains, inverse and cousin lookups, interpolation and tf2's errors. Composition,
inversion and slerp are checked against Bullet's LinearMath (pybullet), the library tf2's math comes from."""

from __future__ import annotations

import math

import pybullet
import pytest

from diffctl.tf2.buffer_core import BufferCore
from diffctl.tf2.exceptions import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TransformException,
)

S = 1_000_000_000


def yaw(angle: float) -> tuple[float, float, float, float]:
    return (0.0, 0.0, math.sin(angle / 2), math.cos(angle / 2))


def rpy(r: float, p: float, y: float) -> tuple[float, float, float, float]:
    return tuple(pybullet.getQuaternionFromEuler([r, p, y]))  # type: ignore[return-value]


def close(a, b, tol: float = 1e-6) -> bool:
    return all(abs(x - y) < tol for x, y in zip(a, b, strict=True))


def same_rotation(a, b, tol: float = 1e-6) -> bool:
    return close(a, b, tol) or close(a, [-c for c in b], tol)


@pytest.fixture
def core() -> BufferCore:
    c = BufferCore()
    assert c.set_transform("map", "odom", 0, (1.0, 2.0, 0.0), yaw(0.3), is_static=True) is None
    assert c.set_transform("odom", "base_link", 5 * S, (0.5, -0.2, 0.1), rpy(0.1, -0.2, 1.0)) is None
    assert c.set_transform("base_link", "laser", 0, (0.2, 0.0, 0.3), rpy(0.0, 0.0, math.pi), is_static=True) is None
    assert c.set_transform("base_link", "wheel", 5 * S, (0.0, 0.15, 0.0), rpy(-math.pi / 2, 0.0, 0.0)) is None
    return c


def test_a_chain_and_its_inverse_compose_as_bullet_does(core: BufferCore) -> None:
    a = pybullet.multiplyTransforms([1.0, 2.0, 0.0], yaw(0.3), [0.5, -0.2, 0.1], rpy(0.1, -0.2, 1.0))
    expected = pybullet.multiplyTransforms(a[0], a[1], [0.2, 0.0, 0.3], rpy(0.0, 0.0, math.pi))
    stamp, t, q = core.lookup_transform("map", "laser", 0)
    assert stamp == 5 * S  # the latest common time
    assert close(t, expected[0]) and same_rotation(q, expected[1])
    inv = pybullet.invertTransform(*expected)
    _, t, q = core.lookup_transform("laser", "map", 5 * S)
    assert close(t, inv[0]) and same_rotation(q, inv[1])


def test_cousin_frames_go_through_their_common_parent(core: BufferCore) -> None:
    laser = ([0.2, 0.0, 0.3], rpy(0.0, 0.0, math.pi))
    wheel = ([0.0, 0.15, 0.0], rpy(-math.pi / 2, 0.0, 0.0))
    expected = pybullet.multiplyTransforms(*pybullet.invertTransform(*wheel), *laser)
    _, t, q = core.lookup_transform("wheel", "laser", 0)
    assert close(t, expected[0]) and same_rotation(q, expected[1])
    assert core.can_transform("wheel", "laser", 5 * S) == (True, "")


@pytest.mark.parametrize("q1", [yaw(0.2), yaw(-3.0)])  # the second takes the short way round through ±pi
def test_interpolation_is_linear_and_slerp(q1) -> None:
    c = BufferCore()
    q0, q2 = rpy(0.3, 0.1, 0.0), rpy(0.0, 0.2, 2.9)
    c.set_transform("odom", "base", 10 * S, (0.0, 0.0, 0.0), q0)
    c.set_transform("odom", "base", 12 * S, (2.0, -4.0, 1.0), q1)
    c.set_transform("odom", "base", 14 * S, (3.0, -4.0, 1.0), q2)
    _, t, q = c.lookup_transform("odom", "base", 13 * S + S // 2)
    assert close(t, (2.75, -4.0, 1.0))
    assert same_rotation(q, pybullet.getQuaternionSlerp(q1, q2, 0.75), 1e-6)
    _, t, q = c.lookup_transform("base", "odom", 11 * S)
    expected = pybullet.invertTransform([1.0, -2.0, 0.5], pybullet.getQuaternionSlerp(q0, q1, 0.5))
    assert close(t, expected[0]) and same_rotation(q, expected[1])


def test_errors_are_tf2s(core: BufferCore) -> None:
    with pytest.raises(LookupException) as e:
        core.lookup_transform("base", "laser", 0)
    assert str(e.value) == '"base" passed to lookupTransform argument target_frame does not exist. '
    with pytest.raises(ExtrapolationException) as e:
        core.lookup_transform("map", "laser", 6 * S)
    assert str(e.value) == (
        "Lookup would require extrapolation at time 6.000000, but only time 5.000000 is in the buffer, "
        "when looking up transform from frame [laser] to frame [map]"
    )
    core.set_transform("odom", "base_link", 7 * S, (0.0, 0.0, 0.0), yaw(0.0))
    with pytest.raises(ExtrapolationException) as e:
        core.lookup_transform("map", "base_link", 8 * S)
    assert str(e.value) == (
        "Lookup would require extrapolation into the future.  Requested time 8.000000 but the latest data is "
        "at time 7.000000, when looking up transform from frame [base_link] to frame [map]"
    )
    with pytest.raises(ExtrapolationException) as e:
        core.lookup_transform("base_link", "map", 4 * S)
    assert "into the past.  Requested time 4.000000 but the earliest data is at time 5.000000" in str(e.value)
    core.set_transform("world", "other", 0, (0.0, 0.0, 0.0), yaw(0.0))
    with pytest.raises(ConnectivityException) as e:
        core.lookup_transform("map", "other", 0)
    assert str(e.value) == (
        "Could not find a connection between 'map' and 'other' because they are not part of the same tree."
        "Tf has two or more unconnected trees."
    )
    with pytest.raises(InvalidArgumentException) as e:
        core.lookup_transform("/map", "laser", 0)
    assert "in tf2 frame_ids cannot start with a '/'" in str(e.value)
    assert isinstance(e.value, TransformException)
    assert core.can_transform("nope", "laser", 0) == (
        False, 'Invalid frame ID "nope" passed to canTransform argument target_frame - frame does not exist')


def test_bad_input_is_refused_and_old_data_expires() -> None:
    c = BufferCore(cache_time_ns=2 * S)
    assert "TF_SELF_TRANSFORM" in (c.set_transform("a", "a", S, (0, 0, 0), yaw(0)) or "")
    assert "TF_DENORMALIZED_QUATERNION" in (c.set_transform("a", "b", S, (0, 0, 0), (0, 0, 0, 2.0)) or "")
    assert "TF_NAN_INPUT" in (c.set_transform("a", "b", S, (math.nan, 0, 0), yaw(0)) or "")
    for sec in range(1, 6):
        assert c.set_transform("a", "b", sec * S, (float(sec), 0, 0), yaw(0)) is None
    assert "TF_OLD_DATA" in (c.set_transform("a", "b", 1 * S, (0, 0, 0), yaw(0)) or "")
    with pytest.raises(ExtrapolationException):
        c.lookup_transform("a", "b", 2 * S)  # pruned: more than 2 s behind the newest
    assert c.lookup_transform("a", "b", 3 * S)[1] == (3.0, 0.0, 0.0)
    assert c.lookup_transform("a", "a", 0) == (0, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
    assert "b: \n  parent: 'a'\n" in c.all_frames_as_yaml()
