"""force_torque_sensor_broadcaster/ForceTorqueSensorBroadcaster (Jazzy): a force-torque sensor's state interfaces
as geometry_msgs/msg/WrenchStamped on `~/wrench` (SystemDefaultsQoS), every update, in `frame_id`.

The sensor is named either by `sensor_name` (the six standard interfaces `<sensor_name>/force.x` …) or axis by
axis (`interface_names.force.x` …, missing axes read 0) — one of the two, as upstream. Each value has its
`offset.*` added, then is multiplied by `multiplier.*` (both may change while it runs). It is chainable: it exports
the corrected values as state interfaces `<controller>/<sensor_name>/force.x` … (or `<controller>/<interface>`
per named axis), updated every cycle. `sensor_filter_chain` (the filters package's plugins) is not available
here: given, it is reported and `~/wrench_filtered` stays silent, as upstream does with no filters.
"""

from __future__ import annotations

from typing import Any

from diffctl.client.interfaces import cls
from diffctl.control.controller_interface import (
    CallbackReturn,
    ChainableControllerInterface,
    ReturnType,
    StateInterface,
)
from diffctl.control.controllers.param_decl import (
    Check,
    ParamDecl,
    changed_values,
    current_values,
    declare_all,
    overrides,
    read_declared,
    table,
)
from diffctl.control.controllers.semantic_components import WRENCH_FIELDS, wrench_interfaces
from diffctl.control.controllers.sensor_broadcasting import SensorBroadcasting

WRENCH = "geometry_msgs/msg/WrenchStamped"
_AXES = [("force", a) for a in "xyz"] + [("torque", a) for a in "xyz"]
_AROUND = {"force": "on '{a}' axis", "torque": "around '{a}' axis"}


def _axis_decls() -> list[ParamDecl]:
    out = []
    for group, a in _AXES:
        where = _AROUND[group].format(a=a)
        out.append(ParamDecl(f"interface_names.{group}.{a}", "string", "",
                             f"Name of the state interface with {group} values {where}."))
    for group, a in _AXES:
        out.append(ParamDecl(f"offset.{group}.{a}", "double", 0.0, f"The offset of {group} values {_AROUND[group]}."
                             .format(a=a)))
    for group, a in _AXES:
        out.append(ParamDecl(f"multiplier.{group}.{a}", "double", 1.0,
                             f"The multiplier of {group} value {_AROUND[group]}.".format(a=a)))
    return out


DECLS = table([
    ParamDecl("frame_id", "string", "", "Sensor's frame_id in which values are published.",
              checks=(Check("not_empty", ()),)),
    ParamDecl("sensor_name", "string", "", "Name of the sensor used as prefix for interfaces if there are no "
              "individual interface names defined.\n    If used, standard interface names for a 6D FTS will be "
              "used: ``<sensor_name>/force.x, ..., <sensor_name>/torque.z``"),
    *_axis_decls(),
])  # fmt: skip


class ForceTorqueSensorBroadcaster(SensorBroadcasting, ChainableControllerInterface):
    def __init__(self) -> None:
        super().__init__()
        self._correction: tuple[tuple[float, float], ...] = ((0.0, 1.0),) * 6

    def on_init(self) -> None:
        node = self.get_node()
        given = overrides(node)
        self.values = declare_all(node, DECLS, self.get_name())
        if any(k.startswith("sensor_filter_chain.") for k in given):
            node.get_logger().warn("'sensor_filter_chain' is set, but filter plugins are not available in diffctl: "
                                   "~/wrench_filtered will not be published")
        node.add_on_set_parameters_callback(self._on_set)

    def _on_set(self, parameters: list[Any]) -> Any:
        from diffctl.control.controllers.param_decl import set_result

        try:
            values = read_declared(DECLS, changed_values(self.get_node(), DECLS, parameters), self.get_name())
        except Exception as e:  # ParameterError: refused with its reason
            return set_result(str(e))
        self._correction = _correction(values)  # taken by the next update, as the parameter listener's is_old
        return set_result(None)

    def sensor_interfaces(self) -> list[str]:
        v = self.values
        return wrench_interfaces(v["sensor_name"], [v[f"interface_names.{g}.{a}"] for g, a in _AXES])

    def on_configure(self, previous_state: Any) -> CallbackReturn:
        node = self.get_node()
        self.values = v = read_declared(DECLS, current_values(node, DECLS), self.get_name())
        named_axes = any(v[f"interface_names.{g}.{a}"] for g, a in _AXES)
        if not v["sensor_name"] and not named_axes:
            node.get_logger().error("'sensor_name' or at least one 'interface_names.[force|torque].[x|y|z]' parameter "
                                    "has to be specified.")
            return CallbackReturn.ERROR
        if v["sensor_name"] and named_axes:
            node.get_logger().error("both 'sensor_name' and 'interface_names.[force|torque].[x|y|z]' parameters can "
                                    "not be specified together.")
            return CallbackReturn.ERROR
        self._correction = _correction(v)
        msg = cls(WRENCH)()
        msg.header.frame_id = v["frame_id"]
        leaves = [(f"wrench.{f}", "d") for f in WRENCH_FIELDS]
        self.open_publishers(msg, WRENCH, ["~/wrench", "~/wrench_filtered"], leaves)
        node.get_logger().info("configure successful")
        return CallbackReturn.SUCCESS

    def on_export_state_interfaces(self) -> list[StateInterface]:
        v = self.values
        out = []
        for k, name in enumerate(self.sensor_interfaces()):
            if not name:
                continue
            if v["sensor_name"]:
                out.append(StateInterface(f"{self.get_name()}/{v['sensor_name']}/{WRENCH_FIELDS[k]}", 0.0))
            else:
                out.append(StateInterface(f"{self.get_name()}/{name}", 0.0))
        self._exported_axes = [k for k, name in enumerate(self.sensor_interfaces()) if name]
        return out

    def update_reference_from_subscribers(self, time: Any, period: Any) -> ReturnType:
        return ReturnType.OK

    def update_and_write_commands(self, time: Any, period: Any) -> ReturnType:
        wrench = [(value + offset) * gain
                  for value, (offset, gain) in zip(self.sensor_values(), self._correction, strict=True)]
        self.publish_stamped(time, wrench)
        for handle, k in zip(self.exported_state_interfaces, self._exported_axes, strict=True):
            handle.value = wrench[k]
        return ReturnType.OK


def _correction(v: dict[str, Any]) -> tuple[tuple[float, float], ...]:
    return tuple((v[f"offset.{g}.{a}"], v[f"multiplier.{g}.{a}"]) for g, a in _AXES)
