"""A test's own presence on the bus (bench.probe.Probe: raw endpoints, synchronous calls, the graph), and a
client Node of the test process spinning on a thread, for a test that needs a full ROS node of its own."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from bench.probe import Probe, call
from diffctl.client.context import Context
from diffctl.client.executors import ExternalShutdownException, SingleThreadedExecutor
from diffctl.client.node import Node

__all__ = ["Probe", "call", "parameters", "probe", "spinning"]


def probe(name: str, namespace: str = "/") -> Probe:
    return Probe(name, namespace)


def parameters(p: Probe, node_fqn: str) -> dict[str, Any]:
    """Every parameter of a node with its descriptor (rcl_interfaces/msg/ParameterDescriptor), by name."""
    names = list(call(p, f"{node_fqn}/list_parameters", "rcl_interfaces/srv/ListParameters").result.names)
    described = call(p, f"{node_fqn}/describe_parameters", "rcl_interfaces/srv/DescribeParameters",
                     {"names": names}).descriptors
    return {str(d.name): d for d in described}


@contextmanager
def spinning(name: str, **kw: Any) -> Iterator[Node]:
    """A client Node of this process, its executor spinning on a thread (its services answer)."""
    context = Context()
    context.init(args=[])
    node = Node(name, context=context, **kw)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    def spin() -> None:
        try:
            executor.spin()
        except ExternalShutdownException:
            pass

    thread = threading.Thread(target=spin, daemon=True)
    thread.start()
    try:
        yield node
    finally:
        context.try_shutdown()
        thread.join(5.0)
        node.destroy_node()
