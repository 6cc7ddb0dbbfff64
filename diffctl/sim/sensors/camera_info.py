"""gz.msgs.CameraInfo of a pinhole camera as gz-sensors fills it (pure math, no rendering).

Without `<lens><intrinsics>` Gazebo reads K and P back from the render projection
(gz-rendering `projectionToCameraIntrinsic`): for the symmetric frustum a horizontal field of view and the
image's aspect ratio give, fx = fy = W / (2 tan(hfov / 2)), cx = W / 2, cy = H / 2. Distortion is PLUMB_BOB
with k = [k1, k2, p1, p2, k3] (zero: the renderer draws an ideal pinhole), R is the identity.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from diffctl.bus import gz


@dataclass(frozen=True)
class Intrinsics:
    fx_px: float
    fy_px: float
    cx_px: float
    cy_px: float

    @property
    def k(self) -> list[float]:
        return [self.fx_px, 0.0, self.cx_px, 0.0, self.fy_px, self.cy_px, 0.0, 0.0, 1.0]

    @property
    def p(self) -> list[float]:
        # A monocular camera: no baseline, so Tx = Ty = 0.
        return [self.fx_px, 0.0, self.cx_px, 0.0, 0.0, self.fy_px, self.cy_px, 0.0, 0.0, 0.0, 1.0, 0.0]


def focal_length_px(width_px: int, horizontal_fov_rad: float) -> float:
    return width_px / (2.0 * math.tan(horizontal_fov_rad / 2.0))


def intrinsics_from_fov(width_px: int, height_px: int, horizontal_fov_rad: float) -> Intrinsics:
    f = focal_length_px(width_px, horizontal_fov_rad)
    return Intrinsics(f, f, width_px / 2.0, height_px / 2.0)


IDENTITY_3X3 = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]


def camera_info_msg(sim_time_ns: int, frame: str, width_px: int, height_px: int, intr: Intrinsics) -> dict:
    return {
        "header": gz.header(sim_time_ns, frame),
        "width": width_px,
        "height": height_px,
        "distortion": {"model": "PLUMB_BOB", "k": [0.0] * 5},
        "intrinsics": {"k": intr.k},
        "projection": {"p": intr.p},
        "rectification_matrix": list(IDENTITY_3X3),
    }
