"""rclpy.publisher.Publisher on a bus publisher: messages serialized by the message classes' codec."""

from __future__ import annotations

from typing import Any

from diffctl.client.duration import Duration
from diffctl.client.endpoint_statuses import EndpointStatuses
from diffctl.client.exceptions import InvalidHandle, RCLError
from diffctl.client.interfaces import serialize
from diffctl.client.node_entity import NodeEntity


class Publisher(NodeEntity):
    def __init__(self, publisher_impl: Any, msg_type: Any, topic: str, qos_profile: Any, *,
                 event_callbacks: Any, callback_group: Any) -> None:
        """rclpy's signature (subclasses such as LifecyclePublisher pass it through); `publisher_impl` is the
        bus publisher, carrying the client node that made it."""
        bus_pub = publisher_impl
        self._node = bus_pub.client_node
        self._bus = bus_pub
        self._bus_topic = bus_pub.topic
        self.msg_type = msg_type
        self.topic = topic
        self.qos_profile = qos_profile
        self.callback_group = callback_group
        self._publish_raw = bus_pub.publish_raw
        self._context = self._node.context
        self._destroyed = False
        self.qos_statuses = EndpointStatuses(qos_profile)
        self.event_handlers = event_callbacks.create_event_handlers(callback_group, self, topic)
        self._on_write = self.qos_statuses.write_hook(self)

    def publish(self, msg: Any) -> None:
        if self._destroyed:
            raise InvalidHandle("cannot use Destroyable because destruction was requested")
        if not self._context._ok:
            raise context_invalid("Failed to publish")
        if type(msg) is self.msg_type or isinstance(msg, self.msg_type):
            data = serialize(msg)
        elif isinstance(msg, (bytes, bytearray)):
            data = bytes(msg)
        else:
            raise TypeError(f"Expected {self.msg_type}, got {type(msg)}")
        try:
            self._publish_raw(data)
            if self._on_write is not None:
                self._on_write()
        except Exception as e:  # zenoh.ZError: the session closed under a callback still running at exit
            if "closed" in str(e):
                raise context_invalid("Failed to publish") from None
            raise

    def get_subscription_count(self) -> int:
        if not self._context._ok:
            raise context_invalid("failed to get subscription count")
        return self._bus.subscription_count

    @property
    def topic_name(self) -> str:
        return self._bus_topic

    def destroy(self) -> None:
        self._node.destroy_publisher(self)

    def _destroy(self) -> None:
        if not self._destroyed:
            self._destroyed = True
            for h in self.event_handlers:
                h.destroy()
            self.qos_statuses.close()
            self._bus.close()

    def assert_liveliness(self) -> None:
        if not self._context._ok:
            raise context_invalid("Failed to assert liveliness on the Publisher")
        self.qos_statuses.assert_liveliness(self)

    def wait_for_all_acked(self, timeout: Duration = Duration(seconds=-1)) -> bool:
        if not self._context._ok:
            raise context_invalid("Failed to wait for all acknowledgements")
        return True  # Zenoh's reliable channel has handed every sample over once put returns


def context_invalid(what: str) -> RCLError:
    """rcl's refusal of a publisher whose context was shut down."""
    return RCLError(f"{what}: publisher's context is invalid, at /project/src/rcl/publisher.c:423")
