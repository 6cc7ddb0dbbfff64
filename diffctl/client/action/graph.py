"""rclpy.action.graph: actions found in the graph by their hidden feedback topics (as rcl_action does)."""

from __future__ import annotations

from typing import Any

_SUFFIX = "/_action/feedback"
_TYPE_SUFFIX = "_FeedbackMessage"


def _actions(names_and_types: list[tuple[str, list[str]]]) -> list[tuple[str, list[str]]]:
    found = []
    for name, types in names_and_types:
        if name.endswith(_SUFFIX):
            found.append((name[: -len(_SUFFIX)], [t[: -len(_TYPE_SUFFIX)] for t in types if t.endswith(_TYPE_SUFFIX)]))
    return sorted(found)


def get_action_names_and_types(node: Any) -> list[tuple[str, list[str]]]:
    return _actions(node.get_topic_names_and_types())


def get_action_server_names_and_types_by_node(node: Any, remote_node_name: str,
                                              remote_node_namespace: str) -> list[tuple[str, list[str]]]:
    return _actions(node.get_publisher_names_and_types_by_node(remote_node_name, remote_node_namespace))


def get_action_client_names_and_types_by_node(node: Any, remote_node_name: str,
                                              remote_node_namespace: str) -> list[tuple[str, list[str]]]:
    return _actions(node.get_subscriber_names_and_types_by_node(remote_node_name, remote_node_namespace))
