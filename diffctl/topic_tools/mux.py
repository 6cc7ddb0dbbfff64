"""mux and demux: one of many inputs to one output, one input to one of many outputs, switched by the
~/select service (topic_tools_interfaces) and extended by ~/add, ~/delete and ~/list. `__none` selects
nothing."""

from __future__ import annotations

from typing import Any

from diffctl.interfaces import get_interface
from diffctl.topic_tools.relay import Relay
from diffctl.topic_tools.tools import required

NONE_TOPIC = "__none"


class Switch:
    """The topic list and the selected one; `kind` is "mux" (inputs) or "demux" (outputs)."""

    def __init__(self, node: Any, kind: str) -> None:
        self.node, self.kind, self.log = node, kind, node.get_logger()
        initial = node.declare_parameter("initial_topic", "").value
        if kind == "mux":
            output = node.declare_parameter("output_topic", "~/selected").value
            lazy = node.declare_parameter("lazy", False).value
            self.topics = list(required(node, "input_topics", "STRING_ARRAY"))
            self._selected = initial or (self.topics[0] if self.topics else NONE_TOPIC)
            self.relay = Relay(node, self._selected, output, lazy, self._forward, self._active)
        else:
            source = node.declare_parameter("input_topic", "~/input").value
            self.topics = list(required(node, "output_topics", "STRING_ARRAY"))
            self._selected = initial or (self.topics[0] if self.topics else NONE_TOPIC)
            self.relay = Relay(node, source, self._selected, False, self._forward, self._active)
        srv = f"topic_tools_interfaces/srv/{kind.capitalize()}"
        node.create_service(get_interface(srv + "Add"), "~/add", self.on_add)
        node.create_service(get_interface(srv + "Delete"), "~/delete", self.on_delete)
        node.create_service(get_interface(srv + "List"), "~/list", self.on_list)
        node.create_service(get_interface(srv + "Select"), "~/select", self.on_select)

    @property
    def selected(self) -> str:
        return self._selected

    @selected.setter
    def selected(self, topic: str) -> None:
        self._selected = topic
        if self.kind == "mux":
            self.relay.input_topic = topic
        else:
            self.relay.output_topic = topic

    def _forward(self, data: bytes) -> None:
        self.relay.publish(data)

    def _active(self) -> bool:
        return self.selected != NONE_TOPIC or self.selected in self.topics

    def decide(self) -> None:
        if self._active():
            self.relay.decide()

    def _find(self, topic: str) -> int | None:
        resolve = self.node.resolve_topic_name
        wanted = resolve(topic)
        return next((i for i, t in enumerate(self.topics) if resolve(t) == wanted), None)

    def on_add(self, request: Any, response: Any) -> Any:
        kind = self.kind
        self.log.info(f"trying to add {request.topic} to {kind}")
        if request.topic == NONE_TOPIC:
            self.log.warning(f"failed to add topic {request.topic} to {kind}, because it's reserved for special use")
            response.success = False
        elif request.topic in self.topics:
            self.log.warning(f"tried to add a topic that {kind} was already listening to: [{request.topic}]")
            response.success = False
        else:
            self.topics.append(request.topic)
            self.log.info(f"added {request.topic} to {kind}")
            response.success = True
        return response

    def on_delete(self, request: Any, response: Any) -> Any:
        kind = self.kind
        self.log.info(f"trying to delete {request.topic} to {kind}")
        i = self._find(request.topic)
        if i is None:
            self.log.warning(f"tried to delete non-subscribed topic {request.topic} from {kind}")
            response.success = False
        elif self.node.resolve_topic_name(self.selected) == self.node.resolve_topic_name(request.topic):
            self.log.warning(f"tried to delete currently selected topic {request.topic} from {kind}")
            response.success = False
        else:
            del self.topics[i]
            self.log.info(f"deleted topic {request.topic} from {kind}")
            response.success = True
        return response

    def on_list(self, request: Any, response: Any) -> Any:
        response.topics = list(self.topics)
        return response

    def on_select(self, request: Any, response: Any) -> Any:
        kind = self.kind
        response.prev_topic = self.selected if self.selected != NONE_TOPIC and self._find(self.selected) is not None \
            else ""
        if request.topic == NONE_TOPIC:
            self.log.info(f"{kind} selected to no input.")
            self.selected = NONE_TOPIC
            if kind == "mux":
                self.relay.decide()
            response.success = True
        else:
            self.log.info(f"trying to switch {kind} to {request.topic}")
            if self._find(request.topic) is not None:
                self.selected = request.topic
                self.decide()
                self.log.info(f"{kind} selected input: [{request.topic}]")
                response.success = True
        return response
