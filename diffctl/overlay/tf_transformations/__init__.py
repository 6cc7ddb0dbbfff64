"""tf_transformations (Jazzy): tf's transformations.py API, quaternions as [x, y, z, w], from diffctl.tf2
(rotations, Euler angles and quaternions in transformations.py; reflections, scaling, shears, projections,
decomposition, superimposition and random rotations in affine.py). The arcball helpers are not here."""

from diffctl.tf2.affine import *  # noqa: F403
from diffctl.tf2.affine import _AXES2TUPLE, _TUPLE2AXES  # noqa: F401
from diffctl.tf2.affine import __all__ as _affine_names
from diffctl.tf2.transformations import *  # noqa: F403
from diffctl.tf2.transformations import __all__ as _rotation_names

__all__ = [*_rotation_names, *_affine_names]
