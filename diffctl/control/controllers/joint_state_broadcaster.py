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

from diffctl.client.interfaces import cls
from diffctl.client.qos import qos_profile_system_default
from diffctl.control.cdr_template import CdrTemplate
from diffctl.control.controller_interface import ControllerInterface, InterfaceConfiguration, ReturnType
from diffctl.control.controllers.owned_endpoints import OwnedEndpoints
from diffctl.control.controllers.param_decl import (
    Check,
    ParamDecl,
    declare_all,
    overrides,
    read_declared,
    table,
    unknown_key_warnings,
)
from diffctl.control.realtime_publisher import RealtimePublisher
from diffctl.errors import ParameterError, RuntimeFailure

JOINT_STATE = "sensor_msgs/msg/JointState"
DYNAMIC_JOINT_STATE = "control_msgs/msg/DynamicJointState"
_FIELDS = ("position", "velocity", "effort")
_NS = 1_000_000_000
_VALUE = operator.attrgetter("value")  # a handle's value, read in C by map()
_OK = ReturnType.OK
_NAME = (Check("not_empty", ()),)
_UNIQUE = (Check("unique", ()),)

_BOTH = ("If either ``joints`` or ``interfaces`` is left empty, all available state interfaces will be "
         "published.")
# joint_state_broadcaster's `src/joint_state_broadcaster_parameters.yaml` (ros2_controllers, jazzy), in its
# order: every parameter is read-only (they shape the interfaces claimed and the messages built at activation).
DECLS = table(
    [
        ParamDecl("use_local_topics", "bool", False,
                  "Defining if ``joint_states`` and ``dynamic_joint_states`` messages should be published into local "
                  "namespace, e.g., ``/my_state_broadcaster/joint_states``.", True),
        ParamDecl("joints", "string_array", [],
                  "Parameter to support broadcasting of only specific joints and interfaces. It has to be used in "
                  f"combination with the ``interfaces`` parameter. {_BOTH} Joint state broadcaster asks for access "
                  "to all defined interfaces on all defined joints.", True, also=_UNIQUE),
        ParamDecl("extra_joints", "string_array", [],
                  "Names of extra joints to be added to ``joint_states`` and ``dynamic_joint_states`` with state "
                  "set to 0.", True, also=_UNIQUE),
        ParamDecl("interfaces", "string_array", [],
                  "Parameter to support broadcasting of only specific joints and interfaces. It has to be used in "
                  f"combination with the ``joints`` parameter. {_BOTH} If this parameter contains ``position``, "
                  "``velocity``, or ``effort``, the corresponding ``map_interface_to_joint_state.<field>`` setting "
                  "is ignored because the standard interface is already requested directly. A warning is printed "
                  "only when such an ignored mapping is set to a different custom interface name.", True,
                  also=_UNIQUE),
        *(ParamDecl(f"map_interface_to_joint_state.{f}", "string", f, "", True, also=_NAME) for f in _FIELDS),
        ParamDecl("use_urdf_to_filter", "bool", True,
                  "Uses the robot_description to filter the ``joint_states`` topic. If true, the broadcaster will "
                  "publish the data of the joints present in the URDF alone. If false, the broadcaster will publish "
                  "the data of any interface that has type ``position``, ``velocity``, or ``effort``.", True),
        ParamDecl("frame_id", "string", "base_link",
                  "The frame_id to be used in the published joint states. This parameter allows rviz2 to visualize "
                  "the effort of the joints.", True),
        ParamDecl("publish_dynamic_joint_states", "bool", True, "Whether to publish dynamic joint states.", True),
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


def _picker(indices: list[int]) -> Any:
    """values → the tuple of values[i] for i in `indices` (one C call per cycle)."""
    if not indices:
        return lambda _values: ()
    get = operator.itemgetter(*indices)
    return get if len(indices) > 1 else lambda values: (get(values),)


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
        self._handles: list[Any] = []
        # (the publisher's publish_values, template, values → its leaves' values)
        self._fast: list[tuple[Any, CdrTemplate, Any]] = []
        self.joint_names: list[str] = []

    def on_init(self) -> None:
        node = self.get_node()
        self.params, warnings = JointStateBroadcasterParams.from_params(overrides(node), self.get_name())
        for text in warnings:
            node.get_logger().warn(text)
        declare_all(node, DECLS, self.get_name())

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.none()

    def state_interface_configuration(self) -> InterfaceConfiguration:
        p = self.params
        if not p.joints or not p.interfaces:
            return InterfaceConfiguration.all()
        return InterfaceConfiguration.individual([f"{j}/{i}" for j in p.joints for i in p.interfaces])

    def on_configure(self, previous_state: Any) -> None:
        self._close_endpoints()
        # Relative, as upstream: a broadcaster in /robot1 publishes /robot1/joint_states (multi-robot setups).
        local = "~/" if self.params.use_local_topics else ""
        self._js_pub = self._publisher(JOINT_STATE, f"{local}joint_states")
        if self.params.publish_dynamic_joint_states:
            self._djs_pub = self._publisher(DYNAMIC_JOINT_STATE, f"{local}dynamic_joint_states")

    def _publisher(self, type_name: str, topic: str) -> RealtimePublisher:
        pub = self.get_node().create_publisher(cls(type_name), topic, qos_profile_system_default)
        return self._endpoints.keep(RealtimePublisher(pub))

    def on_activate(self, previous_state: Any) -> None:
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
            order = description_joint_names(self.get_robot_description())
            if order is not None:
                published = [j for j in dict.fromkeys(order) if j in published]
        extra = [j for j in p.extra_joints if j not in by_joint]

        # Each message's fixed layout becomes a template; a cycle hands over the stamp and the state values,
        # packed by the publishing thread (names, frames and the extra joints' zeros stay as built here).
        js = cls(JOINT_STATE)(name=[*published, *extra])
        js.header.frame_id = p.frame_id
        for f in _FIELDS:
            setattr(js, f, [math.nan] * len(published) + [0.0] * len(extra))
        js_leaves = [(field, index, si) for index, joint in enumerate(published) for si in by_joint[joint]
                     if (field := fields.get(si.interface_name)) is not None]  # fmt: skip
        js_leaves.sort(key=lambda leaf: (_FIELDS.index(leaf[0]), leaf[1]))  # the message's byte order

        djs = cls(DYNAMIC_JOINT_STATE)(joint_names=[*by_joint, *extra])
        djs.header.frame_id = p.frame_id
        value_class = cls("control_msgs/msg/InterfaceValue")
        djs.interface_values = [
            *(value_class(interface_names=[si.interface_name for si in sis], values=[math.nan] * len(sis))
              for sis in by_joint.values()),
            *(value_class(interface_names=list(_FIELDS), values=[0.0] * 3) for _ in extra),
        ]  # fmt: skip
        self.joint_names = published + extra
        stamp = [("header.stamp.sec", "i"), ("header.stamp.nanosec", "I")]
        # Every state interface's value is read once per cycle (in the claimed order); each message picks its own.
        self._handles = handles = [si for sis in by_joint.values() for si in sis]
        position = {id(si): k for k, si in enumerate(handles)}
        self._fast = []
        if self._js_pub is not None:
            template = CdrTemplate(js, JOINT_STATE, stamp + [(f"{f}[{i}]", "d") for f, i, _ in js_leaves])
            pick = _picker([position[id(si)] for _, _, si in js_leaves])
            self._fast.append((self._js_pub.publish_values, template, pick))
        if self._djs_pub is not None:
            leaves = [f"interface_values[{j}].values[{k}]" for j, sis in enumerate(by_joint.values())
                      for k in range(len(sis))]  # fmt: skip
            template = CdrTemplate(djs, DYNAMIC_JOINT_STATE, stamp + [(leaf, "d") for leaf in leaves])
            self._fast.append((self._djs_pub.publish_values, template, tuple))

    def on_deactivate(self, previous_state: Any) -> None:
        self._fast = []

    def on_cleanup(self, previous_state: Any) -> None:
        self._close_endpoints()

    def on_shutdown(self, previous_state: Any) -> None:
        self._close_endpoints()

    def update(self, time: Any, period: Any) -> ReturnType:
        return self.update_ns(time.nanoseconds, period.nanoseconds)

    def update_ns(self, time_ns: int, period_ns: int) -> ReturnType:
        """update() on integer nanoseconds (the manager's cycle calls this one: no Time object per cycle)."""
        stamp = divmod(time_ns, _NS)
        values = tuple(map(_VALUE, self._handles))
        for put, template, pick in self._fast:
            put(template, stamp + pick(values))
        return _OK

    def _close_endpoints(self) -> None:
        self._endpoints.close_all()
        self._js_pub = self._djs_pub = None
