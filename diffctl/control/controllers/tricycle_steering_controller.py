"""tricycle_steering_controller/TricycleSteeringController (Jazzy): two traction wheels (right, left) and one
steering joint, on steering_controllers_library. Parameters beyond the library's: `wheelbase`,
`traction_track_width`, `traction_wheels_radius`, and the deprecated `wheel_track`, `front_wheels_radius`,
`rear_wheels_radius` (mapped with a warning)."""

from __future__ import annotations

import sys
from typing import Any

from diffctl.control.controllers.param_decl import Check, ParamDecl, table
from diffctl.control.controllers.steering_controllers_library import SteeringControllersLibrary
from diffctl.control.math.steering_odometry import TRICYCLE

TRICYCLE_DECLS = table([
    ParamDecl("wheel_track", "double", 0.0, "(deprecated) Axle track, use 'traction_track_width' instead"),
    ParamDecl("traction_track_width", "double", 0.0, "Axle track"),
    ParamDecl("wheelbase", "double", 0.0, "Distance between front and rear wheels. For details see: "
              "https://en.wikipedia.org/wiki/Wheelbase", checks=(Check("gt", (0.0,)),)),
    ParamDecl("traction_wheels_radius", "double", 0.0, "Traction wheels radius."),
    ParamDecl("front_wheels_radius", "double", 0.0, "DEPRECATED: Use 'traction_wheels_radius'"),
    ParamDecl("rear_wheels_radius", "double", 0.0, "DEPRECATED: Use 'traction_wheels_radius'"),
])  # fmt: skip


class TricycleSteeringController(SteeringControllersLibrary):
    CONFIG = TRICYCLE
    VARIANT_DECLS = TRICYCLE_DECLS

    def configure_odometry(self, v: dict[str, Any]) -> bool:
        log = self.get_node().get_logger()
        radius, track = v["traction_wheels_radius"], v["traction_track_width"]
        for old in ("front_wheels_radius", "rear_wheels_radius"):
            if v[old] > 0.0:
                singular = old.replace("wheels", "wheel")  # upstream's warning names it so
                log.warn(f"DEPRECATED parameter '{singular}', set 'traction_wheels_radius' instead")
                radius = v[old]
        if v["wheel_track"] > 0.0:
            log.warn("DEPRECATED parameter 'wheel_track', set 'traction_track_width' instead")
            track = v["wheel_track"]
        if track <= sys.float_info.epsilon:
            log.fatal("parameter 'traction_track_width' is not set, cannot configure odometry")
            return False
        self.odometry.set_wheel_params(radius, v["wheelbase"], track)
        log.info("tricycle odometry configure successful")
        return True
