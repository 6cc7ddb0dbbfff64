"""A test's own presence on the bus: a bare node on the wire (diffctl.bus.participant) with raw endpoints,
synchronous service calls and the graph, and nothing a test did not ask for (no parameters, no executor)."""

from __future__ import annotations

import sys
from typing import Any

from diffctl.bus.participant import Participant


class _Stderr:
    def warning(self, text: str) -> None:
        print(f"[probe] {text}", file=sys.stderr)

    error = warning


def probe(name: str, namespace: str = "/") -> Participant:
    return Participant(name, namespace, _Stderr())


def call(p: Participant, service: str, srv_type: str, request: dict[str, Any] | None = None,
         timeout_s: float = 10.0) -> Any:
    """One call of `service`, waiting (bounded) for it to be served."""
    client = p.create_client(service, srv_type)
    try:
        assert client.wait_for_service(timeout_s), f"{service} is not served"
        return client.call(request or {}, timeout=timeout_s)
    finally:
        p.destroy(client)


def parameters(p: Participant, node_fqn: str) -> dict[str, Any]:
    """Every parameter of a node with its descriptor (rcl_interfaces/msg/ParameterDescriptor), by name."""
    names = list(call(p, f"{node_fqn}/list_parameters", "rcl_interfaces/srv/ListParameters").result.names)
    described = call(p, f"{node_fqn}/describe_parameters", "rcl_interfaces/srv/DescribeParameters",
                     {"names": names}).descriptors
    return {str(d.name): d for d in described}
