"""bicycle_steering_controller/BicycleSteeringController (Jazzy): one traction wheel and one steering joint, on
steering_controllers_library. Parameters beyond the library's: `wheelbase`, `traction_wheel_radius`, and the
deprecated `front_wheel_radius` / `rear_wheel_radius` (mapped with a warning)."""

from __future__ import annotations

from typing import Any

from diffctl.control.controllers.param_decl import Check, ParamDecl, table
from diffctl.control.controllers.steering_controllers_library import SteeringControllersLibrary
from diffctl.control.math.steering_odometry import BICYCLE

BICYCLE_DECLS = table([
    ParamDecl("wheelbase", "double", 0.0, "Distance between front and rear wheel. For details see: "
              "https://en.wikipedia.org/wiki/Wheelbase", checks=(Check("gt", (0.0,)),)),
    ParamDecl("traction_wheel_radius", "double", 0.0, "Traction wheel radius."),
    ParamDecl("front_wheel_radius", "double", 0.0, "DEPRECATED: Use 'traction_wheel_radius'", True),
    ParamDecl("rear_wheel_radius", "double", 0.0, "DEPRECATED: Use 'traction_wheel_radius'", True),
])  # fmt: skip


class BicycleSteeringController(SteeringControllersLibrary):
    CONFIG = BICYCLE
    VARIANT_DECLS = BICYCLE_DECLS

    def configure_odometry(self, v: dict[str, Any]) -> bool:
        log = self.get_node().get_logger()
        radius = v["traction_wheel_radius"]
        for old in ("front_wheel_radius", "rear_wheel_radius"):
            if v[old] > 0.0:
                log.warn(f"DEPRECATED parameter '{old}', set 'traction_wheel_radius' instead")
                radius = v[old]
        self.odometry.set_wheel_params(radius, v["wheelbase"])
        log.info("bicycle odometry configure successful")
        return True
