"""imu_sensor_broadcaster/IMUSensorBroadcaster (Jazzy): an IMU's ten state interfaces as sensor_msgs/msg/Imu.

Reads `<sensor_name>/orientation.{x,y,z,w}`, `angular_velocity.{x,y,z}` and `linear_acceleration.{x,y,z}` and
publishes them every update on `~/imu` (SystemDefaultsQoS), stamped with the update's time, in `frame_id`, with
the three static covariances (row-major 3×3). Parameters as `imu_sensor_broadcaster_parameters.yaml`.
"""

from __future__ import annotations

from typing import Any

from diffctl.client.interfaces import cls
from diffctl.control.controller_interface import ControllerInterface, ReturnType
from diffctl.control.controllers.param_decl import Check, ParamDecl, current_values, declare_all, read_declared, table
from diffctl.control.controllers.param_rules import RuleCheck
from diffctl.control.controllers.semantic_components import IMU_FIELDS, imu_interfaces
from diffctl.control.controllers.sensor_broadcasting import SensorBroadcasting

IMU = "sensor_msgs/msg/Imu"
_NINE = (RuleCheck("fixed_size", (9,)),)
_NOT_EMPTY = (Check("not_empty", ()),)

DECLS = table([
    ParamDecl("sensor_name", "string", "", "Defines sensor name used as prefix for its interfaces.\n    Interface "
              "names are: ``<sensor_name>/orientation.x, ..., <sensor_name>/angular_velocity.x, ...,\n    "
              "<sensor_name>/linear_acceleration.x.``", checks=_NOT_EMPTY),
    ParamDecl("frame_id", "string", "", "Sensor's frame_id in which values are published.", checks=_NOT_EMPTY),
    ParamDecl("static_covariance_orientation", "double_array", [0.0] * 9,
              "Static orientation covariance. Row major about x, y, z axes", checks=_NINE),
    ParamDecl("static_covariance_angular_velocity", "double_array", [0.0] * 9,
              "Static angular velocity covariance. Row major about x, y, z axes", checks=_NINE),
    ParamDecl("static_covariance_linear_acceleration", "double_array", [0.0] * 9,
              "Static linear acceleration covariance. Row major about x, y, z axes", checks=_NINE),
])  # fmt: skip

_LEAVES = [*[(f, "d") for f in IMU_FIELDS if f.startswith("orientation")],
           *[(f, "d") for f in IMU_FIELDS if f.startswith("angular")],
           *[(f, "d") for f in IMU_FIELDS if f.startswith("linear")]]


class IMUSensorBroadcaster(SensorBroadcasting, ControllerInterface):
    def on_init(self) -> None:
        self.values = declare_all(self.get_node(), DECLS, self.get_name())

    def sensor_interfaces(self) -> list[str]:
        return imu_interfaces(self.values["sensor_name"])

    def on_configure(self, previous_state: Any) -> None:
        self.values = v = read_declared(DECLS, current_values(self.get_node(), DECLS), self.get_name())
        msg = cls(IMU)()
        msg.header.frame_id = v["frame_id"]
        msg.orientation_covariance = list(v["static_covariance_orientation"])
        msg.angular_velocity_covariance = list(v["static_covariance_angular_velocity"])
        msg.linear_acceleration_covariance = list(v["static_covariance_linear_acceleration"])
        self.open_publishers(msg, IMU, ["~/imu"], _LEAVES)

    def update(self, time: Any, period: Any) -> ReturnType:
        self.publish_stamped(time, self.sensor_values())
        return ReturnType.OK
