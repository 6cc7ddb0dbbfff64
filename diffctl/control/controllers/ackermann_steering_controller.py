"""ackermann_steering_controller/AckermannSteeringController (Jazzy): two traction wheels and two steering joints
(right, left), on steering_controllers_library. Parameters beyond the library's: `wheelbase`, `traction_track_width`,
`steering_track_width` (the traction track when not set), `traction_wheels_radius`, and the deprecated
`front_wheel_track`, `rear_wheel_track`, `front_wheels_radius`, `rear_wheels_radius` (mapped with a warning)."""

from __future__ import annotations

import sys
from typing import Any

from diffctl.control.controllers.param_decl import Check, ParamDecl, table
from diffctl.control.controllers.steering_controllers_library import SteeringControllersLibrary
from diffctl.control.math.steering_odometry import ACKERMANN

_TRACK = "DEPRECATED: use 'traction_track_width' or 'steering_track_width'"
ACKERMANN_DECLS = table([
    ParamDecl("front_wheel_track", "double", 0.0, _TRACK),
    ParamDecl("steering_track_width", "double", 0.0, "(Optional) Steering wheel track length. If not set, "
              "'traction_track_width' will be used."),
    ParamDecl("rear_wheel_track", "double", 0.0, _TRACK),
    ParamDecl("traction_track_width", "double", 0.0, "Traction wheel track length. For details see: "
              "https://en.wikipedia.org/wiki/Wheelbase"),
    ParamDecl("wheelbase", "double", 0.0, "Distance between front and rear wheels. For details see: "
              "https://en.wikipedia.org/wiki/Wheelbase", checks=(Check("gt", (0.0,)),)),
    ParamDecl("traction_wheels_radius", "double", 0.0, "Traction wheels radius."),
    ParamDecl("front_wheels_radius", "double", 0.0, "DEPRECATED: use 'traction_wheels_radius'"),
    ParamDecl("rear_wheels_radius", "double", 0.0, "DEPRECATED: use 'traction_wheels_radius'"),
])  # fmt: skip


class AckermannSteeringController(SteeringControllersLibrary):
    CONFIG = ACKERMANN
    VARIANT_DECLS = ACKERMANN_DECLS

    def configure_odometry(self, v: dict[str, Any]) -> bool:
        log = self.get_node().get_logger()
        radius = v["traction_wheels_radius"]
        for old in ("front_wheels_radius", "rear_wheels_radius"):
            if v[old] > 0.0:
                singular = old.replace("wheels", "wheel")  # upstream's warning names it so
                log.warn(f"DEPRECATED parameter '{singular}', set 'traction_wheels_radius' instead")
                radius = v[old]
        traction_track, steering_track = v["traction_track_width"], v["steering_track_width"]
        for old, front in (("front_wheel_track", True), ("rear_wheel_track", False)):
            if v[old] > 0.0:
                log.warn(f"DEPRECATED parameter '{old}', set 'traction_track_width' or 'steering_track_width' "
                         "instead")
                if front == v["front_steering"]:
                    steering_track = v[old]
                else:
                    traction_track = v[old]
        if radius <= sys.float_info.epsilon:
            log.fatal("parameter 'traction_wheels_radius' is not set, cannot configure odometry")
            return False
        if steering_track <= sys.float_info.epsilon:
            steering_track = traction_track
        self.odometry.set_wheel_params(radius, v["wheelbase"], steering_track, traction_track)
        log.info("Ackermann odom configure successful")
        return True
