"""imu_sensor_broadcaster/IMUSensorBroadcaster (Jazzy): an IMU's ten state interfaces as sensor_msgs/msg/Imu.

Reads `<sensor_name>/orientation.{x,y,z,w}`, `angular_velocity.{x,y,z}` and `linear_acceleration.{x,y,z}` and
publishes them every update on `~/imu` (SystemDefaultsQoS), stamped with the update's time, in `frame_id`, with
the three static covariances (row-major 3×3). Parameters as `imu_sensor_broadcaster_parameters.yaml`.
"""

from __future__ import annotations

from typing import Any

from diffctl.client.interfaces import cls
from diffctl.client.qos import qos_profile_system_default
from diffctl.control.cdr_template import CdrTemplate
from diffctl.control.controller_interface import ControllerInterface, InterfaceConfiguration, ReturnType
from diffctl.control.controllers.owned_endpoints import OwnedEndpoints
from diffctl.control.controllers.param_decl import Check, ParamDecl, declare_all, read_declared, table
from diffctl.control.controllers.param_rules import RuleCheck
from diffctl.control.controllers.semantic_components import IMU_FIELDS, bind, imu_interfaces
from diffctl.control.realtime_publisher import RealtimePublisher

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

_LEAVES = [("header.stamp.sec", "i"), ("header.stamp.nanosec", "I"),
           *[(f, "d") for f in IMU_FIELDS if f.startswith("orientation")],
           *[(f, "d") for f in IMU_FIELDS if f.startswith("angular")],
           *[(f, "d") for f in IMU_FIELDS if f.startswith("linear")]]


class IMUSensorBroadcaster(ControllerInterface):
    def __init__(self) -> None:
        super().__init__()
        self._endpoints = OwnedEndpoints()
        self._pub: Any = None
        self._template: CdrTemplate | None = None
        self._handles: list[Any] = []

    def on_init(self) -> None:
        self.values = declare_all(self.get_node(), DECLS, self.get_name())

    def _params(self) -> dict[str, Any]:
        node = self.get_node()
        return read_declared(DECLS, {n: node.get_parameter(n).value for n in DECLS}, self.get_name())

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.none()

    def state_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual(imu_interfaces(self.values["sensor_name"]))

    def on_configure(self, previous_state: Any) -> None:
        self.values = v = self._params()
        self._endpoints.close_all()
        msg = cls(IMU)()
        msg.header.frame_id = v["frame_id"]
        msg.orientation_covariance = list(v["static_covariance_orientation"])
        msg.angular_velocity_covariance = list(v["static_covariance_angular_velocity"])
        msg.linear_acceleration_covariance = list(v["static_covariance_linear_acceleration"])
        self._msg = msg
        pub = self.get_node().create_publisher(cls(IMU), "~/imu", qos_profile_system_default)
        self._pub = self._endpoints.keep(RealtimePublisher(pub))
        self._template = CdrTemplate(msg, IMU, _LEAVES)

    def on_activate(self, previous_state: Any) -> None:
        self._handles = bind(imu_interfaces(self.values["sensor_name"]), self.state_interfaces)

    def on_deactivate(self, previous_state: Any) -> None:
        self._handles = []

    def on_cleanup(self, previous_state: Any) -> None:
        self._endpoints.close_all()
        self._pub = None

    on_shutdown = on_cleanup

    def update(self, time: Any, period: Any) -> ReturnType:
        sec, nanosec = divmod(time.nanoseconds, 1_000_000_000)
        self._pub.publish_values(self._template, (sec, nanosec, *[h.value for h in self._handles]))
        return ReturnType.OK
