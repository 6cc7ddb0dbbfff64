"""joint_state_broadcaster/JointStateBroadcaster: every state interface out as /joint_states (Jazzy tip).

Claims no command interfaces and, unless both `joints` and `interfaces` are given, all state interfaces.
On every update (so at the controller's update_rate) it publishes
  /joint_states          sensor_msgs/msg/JointState: joints that have a position, velocity or effort
                         interface (after map_interface_to_joint_state), one entry per joint in each of the
                         three arrays, NaN where the joint lacks that interface; then extra_joints at 0.0
  /dynamic_joint_states  control_msgs/msg/DynamicJointState: every interface of every joint, by name
(`~/…` instead with use_local_topics). Joint order: `joints` when given; otherwise the robot description's
joint order when use_urdf_to_filter (dropping interface prefixes that are not joints of the description,
such as sensors); otherwise the order of the interfaces.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from diffctl.bus import types
from diffctl.control.controller_interface import ControllerInterface, InterfaceConfiguration, ReturnType
from diffctl.control.controllers.owned_endpoints import OwnedEndpoints
from diffctl.control.controllers.param_values import ParamReader
from diffctl.errors import RuntimeFailure

JOINT_STATE = "sensor_msgs/msg/JointState"
DYNAMIC_JOINT_STATE = "control_msgs/msg/DynamicJointState"
_FIELDS = ("position", "velocity", "effort")
_NS = 1_000_000_000


@dataclass(frozen=True)
class JointStateBroadcasterParams:
    joints: tuple[str, ...] = ()
    interfaces: tuple[str, ...] = ()
    use_local_topics: bool = False
    extra_joints: tuple[str, ...] = ()
    map_position: str = "position"  # map_interface_to_joint_state.position: interface shown as position
    map_velocity: str = "velocity"
    map_effort: str = "effort"
    use_urdf_to_filter: bool = True
    frame_id: str = "base_link"
    publish_dynamic_joint_states: bool = True

    @property
    def field_of_interface(self) -> dict[str, str]:
        """Interface name → JointState field it fills."""
        return {self.map_position: "position", self.map_velocity: "velocity", self.map_effort: "effort"}

    @classmethod
    def from_params(
        cls, params: Mapping[str, Any], controller: str = "joint_state_broadcaster"
    ) -> tuple[JointStateBroadcasterParams, list[str]]:
        r = ParamReader(params, controller)
        p = cls(
            joints=r.str_list("joints", []),
            interfaces=r.str_list("interfaces", []),
            use_local_topics=r.bool("use_local_topics", False),
            extra_joints=r.str_list("extra_joints", []),
            map_position=r.str("map_interface_to_joint_state.position", "position", non_empty=True),
            map_velocity=r.str("map_interface_to_joint_state.velocity", "velocity", non_empty=True),
            map_effort=r.str("map_interface_to_joint_state.effort", "effort", non_empty=True),
            use_urdf_to_filter=r.bool("use_urdf_to_filter", True),
            frame_id=r.str("frame_id", "base_link"),
            publish_dynamic_joint_states=r.bool("publish_dynamic_joint_states", True),
        )
        if len(set(p.field_of_interface)) != 3:
            raise r.error(
                "map_interface_to_joint_state",
                f"{[p.map_position, p.map_velocity, p.map_effort]!r} maps one interface to two fields",
            )
        warnings = r.unknown_key_warnings()
        if bool(p.joints) != bool(p.interfaces):
            given = "joints" if p.joints else "interfaces"
            warnings.append(f"only '{given}' is set: both 'joints' and 'interfaces' are needed, so all are published")
        return p, warnings


def description_joint_names(description: str) -> list[str] | None:
    """Joint names of the robot description in document order, or None when it cannot be read."""
    if not description.strip():
        return None
    from diffctl.description.sdf_loader import parse_model

    try:
        model = parse_model(description, source="robot_description", check_files=False)
    except Exception:  # an unreadable description just disables the filter, as in the reference
        return None
    return [j.name for j in model.joints]


class JointStateBroadcaster(ControllerInterface):
    def __init__(self) -> None:
        super().__init__()
        self.params = JointStateBroadcasterParams()
        self._endpoints = OwnedEndpoints()
        self._js_pub: Any = None
        self._djs_pub: Any = None
        self._plan: list[tuple[np.ndarray, int, Any]] = []
        self.joint_names: list[str] = []

    def on_init(self) -> None:
        self.params, warnings = JointStateBroadcasterParams.from_params(self.node.params, self.name)
        for text in warnings:
            self.node.log.warn(text)

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.none()

    def state_interface_configuration(self) -> InterfaceConfiguration:
        p = self.params
        if not p.joints or not p.interfaces:
            return InterfaceConfiguration.all()
        return InterfaceConfiguration.individual([f"{j}/{i}" for j in p.joints for i in p.interfaces])

    def on_configure(self) -> None:
        self._close_endpoints()
        local = "~/" if self.params.use_local_topics else "/"
        self._js_pub = self._endpoints.keep(self.node.create_publisher(f"{local}joint_states", JOINT_STATE))
        if self.params.publish_dynamic_joint_states:
            self._djs_pub = self._endpoints.keep(
                self.node.create_publisher(f"{local}dynamic_joint_states", DYNAMIC_JOINT_STATE)
            )

    def on_activate(self) -> None:
        p = self.params
        if not self.state_interfaces:
            raise RuntimeFailure("None of the requested interfaces exist. Controller will not run.")
        by_joint: dict[str, list[Any]] = {}
        for si in self.state_interfaces:
            by_joint.setdefault(si.prefix_name, []).append(si)
        fields = p.field_of_interface

        published = [j for j, sis in by_joint.items() if any(si.interface_name in fields for si in sis)]
        if p.joints:
            published = [j for j in p.joints if j in published]
        elif p.use_urdf_to_filter:
            order = description_joint_names(self.robot_description)
            if order is not None:
                published = [j for j in dict.fromkeys(order) if j in published]
        extra = [j for j in p.extra_joints if j not in by_joint]

        n = len(published) + len(extra)
        js = types.new(JOINT_STATE, {"header": {"frame_id": p.frame_id}, "name": [*published, *extra]})
        arrays = {f: np.full(n, math.nan) for f in _FIELDS}
        for f in _FIELDS:
            arrays[f][len(published) :] = 0.0
            setattr(js, f, arrays[f])
        plan: list[tuple[np.ndarray, int, Any]] = []
        for index, joint in enumerate(published):
            for si in by_joint[joint]:
                field = fields.get(si.interface_name)
                if field is not None:
                    plan.append((arrays[field], index, si))

        djs = types.new(DYNAMIC_JOINT_STATE, {"header": {"frame_id": p.frame_id}})
        djs.joint_names = [*by_joint, *extra]
        value_class = types.get_class("control_msgs/msg/InterfaceValue")
        for sis in by_joint.values():
            values = np.full(len(sis), math.nan)
            djs.interface_values.append(value_class(interface_names=[si.interface_name for si in sis], values=values))
            plan.extend((values, k, si) for k, si in enumerate(sis))
        for _ in extra:
            djs.interface_values.append(value_class(interface_names=list(_FIELDS), values=np.zeros(3)))

        self._joint_state, self._dynamic_joint_state, self._plan = js, djs, plan
        self.joint_names = published + extra

    def on_deactivate(self) -> None:
        self._plan = []

    def on_cleanup(self) -> None:
        self._close_endpoints()

    def on_shutdown(self) -> None:
        self._close_endpoints()

    def update(self, time_ns: int, period_s: float) -> ReturnType:
        for array, index, handle in self._plan:
            array[index] = handle.get_value()
        sec, nanosec = divmod(time_ns, _NS)
        stamp = self._joint_state.header.stamp
        stamp.sec, stamp.nanosec = sec, nanosec
        if self._js_pub is not None:
            self._js_pub.publish(self._joint_state)
        if self._djs_pub is not None:
            stamp = self._dynamic_joint_state.header.stamp
            stamp.sec, stamp.nanosec = sec, nanosec
            self._djs_pub.publish(self._dynamic_joint_state)
        return ReturnType.OK

    def _close_endpoints(self) -> None:
        self._endpoints.close_all()
        self._js_pub = self._djs_pub = None
