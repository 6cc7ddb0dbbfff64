"""Descriptions: immutable, reusable parts of launch_ros's actions (composable nodes, parameters)."""

from ..parameter_descriptions import Parameter, ParameterFile, ParameterValue
from .composable_node import ComposableNode

__all__ = ["ComposableNode", "Parameter", "ParameterFile", "ParameterValue"]
