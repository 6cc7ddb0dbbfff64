"""laser_filters' scan_to_scan_filter_chain on the client Node: `scan` (sensor-data QoS) through the chain its
parameters configure to `scan_filtered` (depth 1000); a scan a filter fails on is not published. With a box
filter, /tf and /tf_static are listened to on threads of their own, so a scan may wait (1 s at most) for its
transform.
"""

from __future__ import annotations

from typing import Any

from diffctl.laser_filters import chain
from diffctl.laser_filters.filters import BoxFilter
from diffctl.laser_filters.scan import from_message, to_message

NODE_NAME = "scan_to_scan_filter_chain"


class BufferTransforms:
    """The box filter's view of a tf2_ros Buffer."""

    def __init__(self, buffer: Any) -> None:
        self.buffer = buffer

    def can_transform(self, target: str, source: str, time_ns: int, timeout_s: float) -> tuple[bool, str]:
        ok, error = self.buffer.can_transform(target, source, time_ns, timeout_s, return_debug_tuple=True)
        return bool(ok), str(error)

    def lookup(self, target: str, source: str, time_ns: int) -> tuple[tuple[float, float, float],
                                                                       tuple[float, float, float, float]]:
        from diffctl.tf2.exceptions import TransformException

        try:
            t = self.buffer.lookup_transform_core(target, source, time_ns).transform
        except TransformException as e:
            raise LookupError(str(e)) from None
        return ((t.translation.x, t.translation.y, t.translation.z),
                (t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w))


def attach(node: Any) -> list[tuple[str, Any]]:
    from diffctl.client.qos import qos_profile_sensor_data
    from diffctl.interfaces import get_interface

    listener: list[Any] = []

    def extra(cls: type) -> dict[str, Any]:
        if cls is not BoxFilter:
            return {}
        if not listener:
            from diffctl.tf2.ros_io import Buffer, TransformListener

            buffer = Buffer(node=node)
            listener.append((TransformListener(buffer, node), BufferTransforms(buffer)))
        return {"transforms": listener[0][1]}

    filters = chain.build(node, extra)
    scan_cls = get_interface("sensor_msgs/msg/LaserScan")
    pub = node.create_publisher(scan_cls, "scan_filtered", 1000)

    def on_scan(msg: Any) -> None:
        out = chain.update(filters, from_message(msg))
        if out is not None:
            pub.publish(to_message(out, scan_cls))

    node.create_subscription(scan_cls, "scan", on_scan, qos_profile_sensor_data)
    return filters


def run() -> int:
    from diffctl.client import component
    from diffctl.client.executors import MultiThreadedExecutor
    from diffctl.client.node import Node

    component.init()  # an executor belongs to an initialised context
    executor = MultiThreadedExecutor(num_threads=2)

    def make() -> Any:
        node = Node(NODE_NAME, client_library="rclcpp")
        attach(node)
        return node

    return component.run(make, executor=executor)
