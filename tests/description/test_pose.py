"""Pose math against an independent numpy construction of the same rotations."""

from __future__ import annotations

import math

import numpy as np
from description_helpers import mat_np, rot_np
from hypothesis import given, settings
from hypothesis import strategies as st

from diffctl.description.pose import Pose

angle = st.floats(-math.pi, math.pi, allow_nan=False)
coord = st.floats(-10, 10, allow_nan=False)


@settings(max_examples=200, deadline=None)
@given(
    st.tuples(coord, coord, coord),
    st.tuples(angle, angle, angle),
    st.tuples(coord, coord, coord),
    st.tuples(angle, angle, angle),
)
def test_compose_inverse_and_matrix_agree_with_numpy(xyz_a, rpy_a, xyz_b, rpy_b) -> None:
    a, b = Pose.from_xyz_rpy(xyz_a, rpy_a), Pose.from_xyz_rpy(xyz_b, rpy_b)
    ma, mb = mat_np(xyz_a, rpy_a), mat_np(xyz_b, rpy_b)
    assert np.allclose(a.to_matrix(), ma, atol=1e-12)
    assert np.allclose((a * b).to_matrix(), ma @ mb, atol=1e-9)
    assert np.allclose(a.inverse().to_matrix(), np.linalg.inv(ma), atol=1e-9)
    assert Pose.from_matrix(ma).is_close(a, 1e-9)
    # rpy round trip through the matrix (angles may differ at gimbal lock; the rotation may not)
    assert np.allclose(rot_np(*a.rpy), ma[:3, :3], atol=1e-7)
    p = (0.3, -1.2, 2.0)
    assert np.allclose(a.transform_point(p), (ma @ np.array([*p, 1.0]))[:3], atol=1e-9)
    assert (a * a.inverse()).is_close(Pose(), 1e-9)
