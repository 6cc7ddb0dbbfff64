"""rclpy.service_introspection: what a service or client publishes on `<service>/_service_event` once
`configure_introspection` turned it on, as rcl does: a `<srv>_Event` per request sent or received and per
response sent or received, with the client's GID and the request's sequence number, and the request or
response itself with CONTENTS."""

from __future__ import annotations

import enum
from typing import Any


class ServiceIntrospectionState(enum.IntEnum):
    OFF = 0  # nothing published
    METADATA = 1  # ServiceEventInfo only
    CONTENTS = 2  # ServiceEventInfo and the request or response


REQUEST_SENT, REQUEST_RECEIVED, RESPONSE_SENT, RESPONSE_RECEIVED = 0, 1, 2, 3  # ServiceEventInfo's constants
SUFFIX = "/_service_event"


class ServiceEvents:
    """One service's or client's event publisher (none while OFF)."""

    def __init__(self, node: Any, srv_type: Any) -> None:
        self._node = node
        self._type = srv_type  # the class, or its name until it is needed
        self._state = ServiceIntrospectionState.OFF
        self._clock: Any = None
        self._pub: Any = None

    @property
    def _srv_type(self) -> Any:
        if isinstance(self._type, str):
            from diffctl.client.interfaces import cls

            self._type = cls(self._type)
        return self._type

    def configure(self, service_name: str, clock: Any, qos: Any, state: ServiceIntrospectionState) -> None:
        state = ServiceIntrospectionState(state)
        if state == ServiceIntrospectionState.OFF:
            self.close()
        elif self._pub is None:
            self._pub = self._node.create_publisher(self._srv_type.Event, service_name + SUFFIX, qos)
        self._clock, self._state = clock, state

    def publish(self, event_type: int, gid: bytes, sequence_number: int, message: Any) -> None:
        if self._pub is None:
            return
        event = self._srv_type.Event()
        info = event.info
        info.event_type = event_type
        info.stamp = self._clock.now().to_msg()
        info.client_gid = list(gid[:16].ljust(16, b"\0"))
        info.sequence_number = sequence_number
        if self._state == ServiceIntrospectionState.CONTENTS:
            if event_type in (REQUEST_SENT, REQUEST_RECEIVED):
                event.request = [message]
            else:
                event.response = [message]
        self._pub.publish(event)

    def close(self) -> None:
        if self._pub is not None:
            self._node.destroy_publisher(self._pub)
            self._pub = None
        self._state = ServiceIntrospectionState.OFF
