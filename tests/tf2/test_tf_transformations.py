"""tf_transformations as Python nodes import it: the values tf's transformations.py documents, and every one of
the 24 axis conventions round-tripping through matrices, quaternions and back (gimbal lock included)."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
import tf_transformations as tft

CONVENTIONS = [
    frame + "".join(p) for frame in "sr" for p in itertools.product("xyz", repeat=3) if p[0] != p[1] and p[1] != p[2]
]


def test_documented_values() -> None:
    # tf's docstrings ([x, y, z, w] quaternions)
    assert np.allclose(tft.quaternion_from_euler(1, 2, 3, "ryxz"), [0.310622, -0.718287, 0.444435, 0.435953])
    assert math.isclose(float(np.sum(tft.euler_matrix(1, 2, 3, "syxz")[0])), -1.34786452, abs_tol=1e-8)
    assert np.allclose(tft.euler_from_quaternion([0.06146124, 0, 0, 0.99810947]), [0.123, 0, 0])
    assert np.allclose(tft.quaternion_multiply([1, -2, 3, 4], [-5, 6, 7, 8]), [-44, -14, 48, 28])
    assert np.allclose(tft.quaternion_about_axis(0.123, (1, 0, 0)), [0.06146124, 0, 0, 0.99810947])
    assert np.allclose(tft.quaternion_from_matrix(np.diag([1.0, -1, -1, 1])), [1, 0, 0, 0])
    assert np.allclose(tft.quaternion_from_matrix(tft.identity_matrix()), [0, 0, 0, 1])
    assert np.allclose(tft.quaternion_matrix([0.06146124, 0, 0, 0.99810947]), tft.rotation_matrix(0.123, (1, 0, 0)))
    assert np.allclose(tft.quaternion_inverse([1, -2, 3, 4]), np.array([-1, 2, -3, 4]) / 30.0)
    q0, q1 = tft.quaternion_about_axis(0.0, (0, 0, 1)), tft.quaternion_about_axis(1.0, (0, 0, 1))
    assert np.allclose(tft.quaternion_slerp(q0, q1, 0.25), tft.quaternion_about_axis(0.25, (0, 0, 1)))
    m = tft.concatenate_matrices(tft.translation_matrix([1, 2, 3]), tft.euler_matrix(0.1, 0.2, 0.3))
    assert np.allclose(tft.translation_from_matrix(m), [1, 2, 3])
    assert tft.is_same_transform(tft.inverse_matrix(m) @ m, tft.identity_matrix())
    with pytest.raises(KeyError):
        tft.euler_matrix(1, 2, 3, "sxxy")


@pytest.mark.parametrize("axes", CONVENTIONS)
def test_every_convention_round_trips(axes: str) -> None:
    rng = np.random.default_rng(7)
    for angles in [
        *((rng.random(3) - 0.5) * 2 * math.pi for _ in range(50)),
        *((0.3, b, 0.7) for b in (0.0, math.pi / 2, -math.pi / 2, math.pi)),
    ]:
        r = tft.euler_matrix(*angles, axes)
        assert np.allclose(r[:3, :3] @ r[:3, :3].T, np.identity(3))
        assert np.allclose(tft.euler_matrix(*tft.euler_from_matrix(r, axes), axes), r)
        q = tft.quaternion_from_euler(*angles, axes)
        assert np.allclose(tft.quaternion_matrix(q), r)
        qm = tft.quaternion_from_matrix(r)
        assert qm[3] >= 0 and (np.allclose(qm, q) or np.allclose(qm, -q))
    # the static sequence reads its angles the other way round from the rotating one
    rot = "r" + axes[3:0:-1] if axes[0] == "s" else "s" + axes[3:0:-1]
    assert np.allclose(tft.euler_matrix(0.1, 0.2, 0.3, axes), tft.euler_matrix(0.3, 0.2, 0.1, rot))
