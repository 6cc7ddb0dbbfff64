"""Evaluated parameters → rclpy Parameter objects for one node (what a container's LoadNode request carries).

Files are read here, as the node would read them: the `/**` section first, then the node's own
(`ns/name`, without leading slashes), nested names joined with '.'.
"""

from __future__ import annotations

import pathlib
import warnings
from typing import TYPE_CHECKING, Any

from diffctl.launch.launch_context import LaunchContext

from ..parameters_type import EvaluatedParameters
from .evaluate_parameters import evaluate_parameter_dict
from .normalize_parameters import normalize_parameter_dict

if TYPE_CHECKING:
    from diffctl.client.parameter import Parameter as RosParameter


def _sections(document: Any) -> dict[str, Any]:
    """`{node path: its ros__parameters}` of a parameter file, keys like `ns/name` or `**`."""
    found: dict[str, Any] = {}

    def walk(tree: Any, path: list[str]) -> None:
        for key, value in tree.items():
            if key == "ros__parameters":
                found["/".join(path)] = value
                return
            if isinstance(value, dict):
                walk(value, [*path, str(key).lstrip("/")])

    if isinstance(document, dict):
        walk(document, [])
    return found


def to_parameters_list(
    context: LaunchContext, node_name: str, namespace: str, evaluated_parameters: EvaluatedParameters
) -> list[RosParameter]:
    """One rclpy Parameter per value, in order (files contribute their `/**` and this node's sections)."""
    import yaml

    from diffctl.client.parameter import Parameter as RosParameter

    node_name = node_name.lstrip("/")
    if namespace and namespace != "/":
        node_name = f"{namespace.strip('/')}/{node_name}"
    out: list[RosParameter] = []
    values: dict[str, Any] = {}
    warned = False
    for entry in evaluated_parameters:
        if isinstance(entry, pathlib.Path):
            document = yaml.safe_load(entry.read_text())
            sections = _sections(document)
            if sections:
                document = dict(sections.get("**", {}))
                document.update(sections.get(node_name, {}))
                if not node_name and not warned:
                    warnings.warn(
                        "node name not provided to launch; parameter files will not apply", UserWarning, stacklevel=2
                    )
                    warned = True
            values = evaluate_parameter_dict(context, normalize_parameter_dict(document)) if document else {}
        else:
            values = entry
        if not isinstance(values, dict):
            raise RuntimeError(f"invalid evaluated parameters {values!r}")
        for name, value in values.items():
            kind = next((t for t in RosParameter.Type if t.check(value)), None)
            if kind is None:
                raise RuntimeError(f"invalid parameter value {value!r}")
            out.append(RosParameter(name, kind, value))
    return out
