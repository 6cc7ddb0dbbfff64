"""interactive_markers' InteractiveMarkerServer (Jazzy, 2.5): markers offered to RViz under a topic namespace.

`<ns>/get_interactive_markers` (GetInteractiveMarkers) answers the markers and the sequence number a client
starts from; `<ns>/update` (InteractiveMarkerUpdate, depth 100) carries each applied batch of changes (whole
markers, poses, erasures) with the next sequence number; `<ns>/feedback` (depth 1) brings the clients' drags
and clicks: a pose update moves the marker, then the marker's callback for that event type (or its default one)
runs. Feedback from a second client within a second of the first one's is ignored.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from diffctl.interfaces import get_interface as msg

POSE_UPDATE = 1  # InteractiveMarkerFeedback.POSE_UPDATE
FULL, POSE, ERASE = "full", "pose", "erase"
Callback = Callable[[Any], None]


@dataclass
class Context:
    marker: Any
    default_cb: Callback | None = None
    callbacks: dict[int, Callback] = field(default_factory=dict)
    last_client: str = ""
    last_feedback_ns: int = 0


@dataclass
class Pending:
    kind: str
    marker: Any = None
    default_cb: Callback | None = None
    callbacks: dict[int, Callback] = field(default_factory=dict)


class InteractiveMarkerServer:
    def __init__(self, topic_namespace: str, node: Any) -> None:
        self.node, self.clock = node, node.get_clock()
        self.contexts: dict[str, Context] = {}
        self.pending: dict[str, Pending] = {}
        self.sequence = 0
        self.update_pub = node.create_publisher(msg("visualization_msgs/msg/InteractiveMarkerUpdate"),
                                                f"{topic_namespace}/update", 100)
        node.create_subscription(msg("visualization_msgs/msg/InteractiveMarkerFeedback"),
                                 f"{topic_namespace}/feedback", self._on_feedback, 1)
        node.create_service(msg("visualization_msgs/srv/GetInteractiveMarkers"),
                            f"{topic_namespace}/get_interactive_markers", self._on_get)

    def insert(self, marker: Any, default_cb: Callback | None = None) -> None:
        old = self.pending.get(marker.name)
        self.pending[marker.name] = Pending(FULL, marker, default_cb if default_cb else
                                            (old.default_cb if old else None), old.callbacks if old else {})

    def set_callback(self, name: str, callback: Callback | None, event_type: int | None = None) -> bool:
        targets = [t for t in (self.contexts.get(name), self.pending.get(name)) if t is not None]
        if not targets:
            return False
        for t in targets:
            if event_type is None:
                t.default_cb = callback
            elif callback is None:
                t.callbacks.pop(event_type, None)
            else:
                t.callbacks[event_type] = callback
        return True

    def set_pose(self, name: str, pose: Any, header: Any = None) -> bool:
        context, pending = self.contexts.get(name), self.pending.get(name)
        if context is None and (pending is None or pending.kind != FULL):
            return False
        if header is None or not header.frame_id:
            header = context.marker.header if context is not None else pending.marker.header
        self._pose(name, pose, header)
        return True

    def _pose(self, name: str, pose: Any, header: Any) -> None:
        pending = self.pending.get(name)
        if pending is None:
            pending = self.pending[name] = Pending(POSE, msg("visualization_msgs/msg/InteractiveMarker")())
        elif pending.kind != FULL:
            pending.kind = POSE
        if pending.marker is None:
            pending.marker = msg("visualization_msgs/msg/InteractiveMarker")()
        pending.marker.pose, pending.marker.header = pose, header

    def erase(self, name: str) -> bool:
        if name not in self.contexts and name not in self.pending:
            return False
        self.pending[name] = Pending(ERASE)
        return True

    def clear(self) -> None:
        self.pending = {name: Pending(ERASE) for name in self.contexts}

    def apply_changes(self) -> None:
        if not self.pending:
            return
        update = msg("visualization_msgs/msg/InteractiveMarkerUpdate")(type=1)  # UPDATE
        pose_cls = msg("visualization_msgs/msg/InteractiveMarkerPose")
        markers, poses, erases = [], [], []
        for name, p in self.pending.items():
            context = self.contexts.get(name)
            if p.kind == FULL:
                if context is None:
                    context = self.contexts[name] = Context(p.marker, p.default_cb, dict(p.callbacks))
                context.marker = p.marker
                markers.append(p.marker)
            elif p.kind == POSE and context is not None:
                context.marker.pose, context.marker.header = p.marker.pose, p.marker.header
                poses.append(pose_cls(header=p.marker.header, pose=p.marker.pose, name=name))
            elif p.kind == ERASE and context is not None:
                del self.contexts[name]
                erases.append(name)
        update.markers, update.poses, update.erases = markers, poses, erases
        self.sequence += 1
        update.seq_num = self.sequence
        self.update_pub.publish(update)
        self.pending.clear()

    def _on_get(self, request: Any, response: Any) -> Any:
        response.sequence_number = self.sequence
        response.markers = [c.marker for c in self.contexts.values()]
        return response

    def _on_feedback(self, feedback: Any) -> None:
        context = self.contexts.get(feedback.marker_name)
        if context is None:
            return
        now = self.clock.now_ns()
        if context.last_client != feedback.client_id and now - context.last_feedback_ns < 1_000_000_000:
            return  # two clients moving one marker: the first keeps it for a second
        context.last_feedback_ns, context.last_client = now, feedback.client_id
        if feedback.event_type == POSE_UPDATE:
            stamp = context.marker.header.stamp
            header = context.marker.header if (stamp.sec, stamp.nanosec) == (0, 0) else feedback.header
            self._pose(feedback.marker_name, feedback.pose, header)
        callback = context.callbacks.get(feedback.event_type) or context.default_cb
        if callback is not None:
            callback(feedback)
