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


def test_affine_family_round_trips_and_geometry() -> None:
    """Reflections, axis rotations, scaling, shears, projections and decomposition give matrices that do what
    they say (a mirror twice is the identity, projected points lie on the plane, …) and whose *_from_matrix
    parameters rebuild the same matrix."""
    rng = np.random.default_rng(7)
    point, normal = rng.random(3) - 0.5, tft.unit_vector(rng.random(3) - 0.5)
    mirror = tft.reflection_matrix(point, normal)
    assert np.allclose(mirror @ mirror, np.identity(4))
    assert np.allclose((mirror @ [*point, 1.0])[:3], point)
    assert np.allclose(tft.reflection_matrix(*tft.reflection_from_matrix(mirror)), mirror)

    turn = tft.rotation_matrix(0.7, [1.0, 2.0, 3.0], point)
    angle, direction, origin = tft.rotation_from_matrix(turn)
    assert np.allclose(tft.rotation_matrix(angle, direction, origin), turn)

    for scaling in (tft.scale_matrix(1.7, point), tft.scale_matrix(-0.4, point, normal)):
        factor, origin, direction = tft.scale_from_matrix(scaling)
        assert np.allclose(tft.scale_matrix(factor, origin, direction), scaling)

    along = tft.unit_vector(np.cross(normal, [0.3, -1.0, 0.2]))
    shear = tft.shear_matrix(0.4, along, point, normal)
    assert np.allclose(tft.shear_matrix(*tft.shear_from_matrix(shear)), shear)

    composed = tft.compose_matrix(scale=[1.0, 2.0, 3.0], shear=[0.1, 0.2, 0.3], angles=[0.3, -0.2, 1.1],
                                  translate=[4.0, 5.0, 6.0])
    scale, shear_factors, angles, translate, perspective = tft.decompose_matrix(composed)
    assert perspective is None
    assert np.allclose(tft.compose_matrix(scale, shear_factors, angles, translate), composed)
    assert np.allclose(translate, [4.0, 5.0, 6.0]) and np.allclose(angles, [0.3, -0.2, 1.1])

    eye = np.array([0.5, 1.0, 4.0])
    cloud = rng.random((3, 5)) * 4.0 - 2.0
    for kwargs in ({}, {"direction": [0.2, 0.1, 1.0]}, {"perspective": eye}):
        projection = tft.projection_matrix(point, normal, **kwargs)
        moved = projection @ np.vstack([cloud, np.ones(5)])
        on_plane = moved[:3] / moved[3]
        assert np.allclose(normal @ (on_plane - point[:, None]), 0.0)
        assert np.allclose(tft.projection_matrix(*tft.projection_from_matrix(projection)), projection)
    pseudo = tft.projection_matrix(point, normal, perspective=eye, pseudo=True)
    assert np.allclose(tft.projection_matrix(*tft.projection_from_matrix(pseudo, pseudo=True)), pseudo)

    box = tft.clip_matrix(-1.0, 3.0, -2.0, 2.0, 1.0, 5.0)
    assert np.allclose(box @ [-1.0, -2.0, 1.0, 1.0], [-1.0, -1.0, -1.0, 1.0])
    frustum = tft.clip_matrix(-1.0, 3.0, -2.0, 2.0, 1.0, 5.0, perspective=True)
    for corner, device in (([-1.0, -2.0, 1.0, 1.0], [-1.0, -1.0, -1.0]), ([3.0, 2.0, 1.0, 1.0], [1.0, 1.0, -1.0])):
        seen = frustum @ corner
        assert np.allclose(seen[:3] / seen[3], device)
    with pytest.raises(ValueError):
        tft.clip_matrix(1.0, 0.0, 0.0, 1.0, 0.0, 1.0)

    cell = tft.orthogonalization_matrix([2.0, 3.0, 4.0], [90.0, 90.0, 90.0])
    assert np.allclose(cell, np.diag([2.0, 3.0, 4.0, 1.0]))


def test_superimposition_random_rotations_and_conventions() -> None:
    """A point set moved rigidly (and scaled) is recovered by both of superimposition_matrix's methods; random
    rotations are proper; a convention tuple names the same Euler matrix as its string; norms fill `out`."""
    rng = np.random.default_rng(11)
    points = rng.random((3, 8)) * 10.0
    motion = tft.concatenate_matrices(tft.translation_matrix([1.0, -2.0, 3.0]), tft.random_rotation_matrix())
    moved = (motion @ np.vstack([points, np.ones(8)]))[:3]
    for usesvd in (True, False):
        assert np.allclose(tft.superimposition_matrix(points, moved, usesvd=usesvd), motion)
    scaled = tft.concatenate_matrices(motion, tft.scale_matrix(2.5))
    grown = (scaled @ np.vstack([points, np.ones(8)]))[:3]
    assert np.allclose(tft.superimposition_matrix(points, grown, scaling=True), scaled)
    with pytest.raises(ValueError):
        tft.superimposition_matrix(points[:, :2], moved[:, :2])

    q = tft.random_quaternion(rng.random(3))
    assert q.shape == (4,) and math.isclose(float(np.dot(q, q)), 1.0)
    r = tft.random_rotation_matrix()[:3, :3]
    assert np.allclose(r @ r.T, np.identity(3)) and math.isclose(float(np.linalg.det(r)), 1.0)
    assert tft.random_vector(5).shape == (5,)

    for name, code in tft._AXES2TUPLE.items():
        assert np.allclose(tft.euler_matrix(0.1, 0.2, 0.3, code), tft.euler_matrix(0.1, 0.2, 0.3, name))
    assert len(tft._AXES2TUPLE) == 24

    vectors = rng.random((4, 3))
    norms = np.empty(4)
    assert tft.vector_norm(vectors, axis=1, out=norms) is None
    assert np.allclose(norms, np.linalg.norm(vectors, axis=1))
    units = np.empty((4, 3))
    tft.unit_vector(vectors, axis=1, out=units)
    assert np.allclose(units, vectors / norms[:, None])
