"""What the sensor broadcasters (IMU, range, force-torque) share: they command nothing, claim one sensor's state
interfaces on activate and let go of them on deactivate, and publish one stamped message per update, serialized
from a template whose leaves are the stamp and the sensor's values; cleanup and shutdown destroy their publishers.

A broadcaster mixes `SensorBroadcasting` in ahead of its controller base and names its interfaces in
`sensor_interfaces` ("" for an axis the sensor lacks, which reads 0).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from diffctl.client.interfaces import cls
from diffctl.client.qos import qos_profile_system_default
from diffctl.control.cdr_template import CdrTemplate
from diffctl.control.controller_interface import InterfaceConfiguration
from diffctl.control.controllers.owned_endpoints import OwnedEndpoints
from diffctl.control.controllers.semantic_components import bind
from diffctl.control.realtime_publisher import RealtimePublisher

_STAMP_LEAVES = (("header.stamp.sec", "i"), ("header.stamp.nanosec", "I"))


class SensorBroadcasting:
    """The lifecycle and publishing half of a sensor broadcaster; `get_node`, `state_interfaces` and the
    lifecycle's call order come from the controller base it is mixed with."""

    get_node: Any
    state_interfaces: Any

    def __init__(self) -> None:
        super().__init__()
        self._endpoints = OwnedEndpoints()
        self._pub: Any = None
        self._template: CdrTemplate | None = None
        self._handles: list[Any] = []

    def sensor_interfaces(self) -> list[str]:
        raise NotImplementedError

    def command_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.none()

    def state_interface_configuration(self) -> InterfaceConfiguration:
        return InterfaceConfiguration.individual([n for n in self.sensor_interfaces() if n])

    def open_publishers(self, msg: Any, type_name: str, topics: Sequence[str], leaves: Sequence[tuple[str, str]]
                        ) -> None:
        """(Re)make the publishers on `topics` (SystemDefaultsQoS); the first one carries `msg`, its stamp and
        `leaves` filled on each `publish_stamped`."""
        self._endpoints.close_all()
        self._template = CdrTemplate(msg, type_name, [*_STAMP_LEAVES, *leaves])
        node = self.get_node()
        pubs = [self._endpoints.keep(RealtimePublisher(node.create_publisher(cls(type_name), topic,
                                                                             qos_profile_system_default)))
                for topic in topics]
        self._pub = pubs[0]

    def on_activate(self, previous_state: Any) -> None:
        self._handles = bind(self.sensor_interfaces(), self.state_interfaces)

    def on_deactivate(self, previous_state: Any) -> None:
        self._handles = []

    def on_cleanup(self, previous_state: Any) -> None:
        self._endpoints.close_all()
        self._pub = None

    def on_shutdown(self, previous_state: Any) -> None:
        self.on_cleanup(previous_state)

    def sensor_values(self) -> list[float]:
        return [h.value if h is not None else 0.0 for h in self._handles]

    def publish_stamped(self, time: Any, values: Sequence[float]) -> None:
        sec, nanosec = divmod(time.nanoseconds, 1_000_000_000)
        self._pub.publish_values(self._template, (sec, nanosec, *values))
