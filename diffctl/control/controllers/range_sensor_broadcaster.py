"""range_sensor_broadcaster/RangeSensorBroadcaster (Jazzy): a `<sensor_name>/range` state interface as
sensor_msgs/msg/Range on `~/range` (SystemDefaultsQoS), every update, stamped with its time, with the sensor's
frame_id, radiation_type, field_of_view, min/max range and variance from the parameters
(`range_sensor_broadcaster_parameters.yaml`). An empty sensor_name or frame_id fails configure, as upstream.
"""

from __future__ import annotations

from typing import Any

from diffctl.client.interfaces import cls
from diffctl.control.controller_interface import CallbackReturn, ControllerInterface, ReturnType
from diffctl.control.controllers.param_decl import ParamDecl, current_values, declare_all, read_declared, table
from diffctl.control.controllers.semantic_components import range_interfaces
from diffctl.control.controllers.sensor_broadcasting import SensorBroadcasting

RANGE = "sensor_msgs/msg/Range"

DECLS = table([
    ParamDecl("sensor_name", "string", "", "Name of the sensor used as prefix for interfaces if there are no "
              "individual interface names defined."),
    ParamDecl("frame_id", "string", "", "Sensor's frame_id in which values are published."),
    ParamDecl("radiation_type", "int", 0, "The type of radiation used by the sensor / 0 = Ultrason / 1 = Infrared"),
    ParamDecl("field_of_view", "double", 0.52, "The size of the arc that the distance reading is valid for [rad]"),
    ParamDecl("min_range", "double", 0.52, "Minimum range value [m]"),
    ParamDecl("max_range", "double", 4.0, "Maximum range value [m]"),
    ParamDecl("variance", "double", 0.0, "Variance of the range value"),
])  # fmt: skip


class RangeSensorBroadcaster(SensorBroadcasting, ControllerInterface):
    def on_init(self) -> None:
        self.values = declare_all(self.get_node(), DECLS, self.get_name())

    def sensor_interfaces(self) -> list[str]:
        return range_interfaces(self.values["sensor_name"])

    def on_configure(self, previous_state: Any) -> CallbackReturn:
        node = self.get_node()
        self.values = v = read_declared(DECLS, current_values(node, DECLS), self.get_name())
        if not v["sensor_name"]:
            node.get_logger().error("'sensor_name' parameter has to be specified.")
            return CallbackReturn.ERROR
        if not v["frame_id"]:
            node.get_logger().error("'frame_id' parameter has to be provided.")
            return CallbackReturn.ERROR
        msg = cls(RANGE)()
        msg.header.frame_id = v["frame_id"]
        msg.radiation_type = v["radiation_type"] & 0xFF  # uint8, as the reference's cast
        msg.field_of_view = v["field_of_view"]
        msg.min_range = v["min_range"]
        msg.max_range = v["max_range"]
        msg.variance = v["variance"]
        self.open_publishers(msg, RANGE, ["~/range"], [("range", "f")])
        return CallbackReturn.SUCCESS

    def update(self, time: Any, period: Any) -> ReturnType:
        self.publish_stamped(time, self.sensor_values())
        return ReturnType.OK
