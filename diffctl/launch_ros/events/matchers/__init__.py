"""Matchers of launch_ros's actions, for targeted events."""

from .matches_node_name import matches_node_name

__all__ = ["matches_node_name"]
