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
import operator
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from diffctl.control.cdr_template import CdrTemplate
from diffctl.control.controller_interface import ControllerInterface, InterfaceConfiguration, ReturnType
from diffctl.control.controllers.owned_endpoints import OwnedEndpoints
from diffctl.control.controllers.param_decl import (
    BASE_DECLS,
    Check,
    ParamDecl,
    declare_all,
    read_declared,
    table,
    unknown_key_warnings,
)
from diffctl.errors import ParameterError, RuntimeFailure
from diffctl.interfaces import types

JOINT_STATE = "sensor_msgs/msg/JointState"
DYNAMIC_JOINT_STATE = "control_msgs/msg/DynamicJointState"
_FIELDS = ("position", "velocity", "effort")
_NS = 1_000_000_000
_VALUE = operator.attrgetter("value")  # a handle's value, read in C by map()
_OK = ReturnType.OK
_NAME = (Check("not_empty", ()),)
_UNIQUE = (Check("unique", ()),)

# joint_state_broadcaster's `src/joint_state_broadcaster_parameters.yaml` (ros2_controllers, jazzy): every
# parameter is read-only: they shape the interfaces claimed and the messages built at activation.
DECLS = table(
    [
        *BASE_DECLS,
        ParamDecl("use_local_topics", "bool", False, "Publish ~/joint_states instead of /joint_states.", True),
        ParamDecl("joints", "string_array", [], "Joints to publish (with interfaces); empty: all.", True, _UNIQUE),
        ParamDecl("extra_joints", "string_array", [], "Joints added with state 0.", True, _UNIQUE),
        ParamDecl("interfaces", "string_array", [], "Interfaces to publish (with joints); empty: all.", True, _UNIQUE),
        *(
            ParamDecl(f"map_interface_to_joint_state.{f}", "string", f, f"Interface published as {f}.", True, _NAME)
            for f in _FIELDS
        ),
        ParamDecl("use_urdf_to_filter", "bool", True, "Publish only joints of the robot description.", True),
        ParamDecl("frame_id", "string", "base_link", "header.frame_id of the messages.", True),
        ParamDecl("publish_dynamic_joint_states", "bool", True, "Publish dynamic_joint_states too.", True),
    ]
)


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
        v = read_declared(DECLS, params, controller)
        p = cls(
            joints=tuple(v["joints"]),
            interfaces=tuple(v["interfaces"]),
            use_local_topics=v["use_local_topics"],
            extra_joints=tuple(v["extra_joints"]),
            map_position=v["map_interface_to_joint_state.position"],
            map_velocity=v["map_interface_to_joint_state.velocity"],
            map_effort=v["map_interface_to_joint_state.effort"],
            use_urdf_to_filter=v["use_urdf_to_filter"],
            frame_id=v["frame_id"],
            publish_dynamic_joint_states=v["publish_dynamic_joint_states"],
        )
        if len(set(p.field_of_interface)) != 3:
            raise ParameterError(
                f"{[p.map_position, p.map_velocity, p.map_effort]!r} maps one interface to two fields",
                field=f"{controller}.map_interface_to_joint_state",
            )
        warnings = unknown_key_warnings(DECLS, params, controller)
        if bool(p.joints) != bool(p.interfaces):
            given = "joints" if p.joints else "interfaces"
            warnings.append(f"only '{given}' is set: both 'joints' and 'interfaces' are needed, so all are published")
        return p, warnings


def description_joint_names(description: str) -> list[str] | None:
    """Joint names of the robot description in document order, or None when it cannot be read."""
    if not description.strip():
        return None
    from diffctl.description.robot_files import parse_description

    try:
        model = parse_description(description, source="robot_description", simulation=False, check_files=False)
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
        self._fast: list[tuple[Any, CdrTemplate, list[Any]]] = []  # (publisher, template, handles of its leaves)
        self.joint_names: list[str] = []

    def on_init(self) -> None:
        self.params, warnings = JointStateBroadcasterParams.from_params(dict(self.node.params), self.name)
        for text in warnings:
            self.node.log.warn(text)
        declare_all(self.node, DECLS, self.name)

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.none()

    def state_interface_configuration(self) -> InterfaceConfiguration:
        p = self.params
        if not p.joints or not p.interfaces:
            return InterfaceConfiguration.all()
        return InterfaceConfiguration.individual([f"{j}/{i}" for j in p.joints for i in p.interfaces])

    def on_configure(self) -> None:
        self._close_endpoints()
        # Relative, as upstream: a broadcaster in /robot1 publishes /robot1/joint_states (multi-robot setups).
        local = "~/" if self.params.use_local_topics else ""
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
        js_leaves: list[tuple[str, int, Any]] = []  # (field, index, handle)
        for index, joint in enumerate(published):
            for si in by_joint[joint]:
                field = fields.get(si.interface_name)
                if field is not None:
                    plan.append((arrays[field], index, si))
                    js_leaves.append((field, index, si))

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
        self._fast = []
        if all(hasattr(pub, "publish_values") for pub in (self._js_pub, self._djs_pub) if pub is not None):
            # The controllers' bus publishers take a template's values: each message's fixed layout becomes a
            # template, and a cycle hands over the stamp and the state values (packed by the publishing
            # thread; the arrays above are then left as activated).
            stamp = [("header.stamp.sec", "i"), ("header.stamp.nanosec", "I")]
            js_leaves.sort(key=lambda leaf: (_FIELDS.index(leaf[0]), leaf[1]))  # the message's byte order
            template = CdrTemplate(js, JOINT_STATE, stamp + [(f"{f}[{i}]", "d") for f, i, _ in js_leaves])
            if self._js_pub is not None:
                self._fast.append((self._js_pub, template, [si for _, _, si in js_leaves]))
            if self._djs_pub is not None:
                leaves = [f"interface_values[{j}].values[{k}]" for j, sis in enumerate(by_joint.values())
                          for k in range(len(sis))]  # fmt: skip
                template = CdrTemplate(djs, DYNAMIC_JOINT_STATE, stamp + [(leaf, "d") for leaf in leaves])
                self._fast.append((self._djs_pub, template, [si for sis in by_joint.values() for si in sis]))

    def on_deactivate(self) -> None:
        self._plan = []
        self._fast = []

    def on_cleanup(self) -> None:
        self._close_endpoints()

    def on_shutdown(self) -> None:
        self._close_endpoints()

    def update(self, time_ns: int, period_s: float) -> ReturnType:
        sec, nanosec = divmod(time_ns, _NS)
        if self._fast:
            for pub, template, handles in self._fast:
                pub.publish_values(template, [sec, nanosec, *map(_VALUE, handles)])
            return _OK
        for array, index, handle in self._plan:
            array[index] = handle.get_value()
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
