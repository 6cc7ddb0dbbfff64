"""tf_transformations (Jazzy): tf's transformations.py API, quaternions as [x, y, z, w], from diffctl.tf2.

The matrix, Euler and quaternion functions Python nodes use are here; the rest of the original module
(reflection, scale, shear, projection, clip, decompose/compose, superimposition, arcball, random_*) is not.
"""

from diffctl.tf2.transformations import *  # noqa: F403
from diffctl.tf2.transformations import __all__  # noqa: F401
