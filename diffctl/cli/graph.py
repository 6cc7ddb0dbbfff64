"""`diffctl node|service|interface …`: the `ros2 node`, `ros2 service` and `ros2 interface` counterparts."""

from __future__ import annotations

import click
import yaml

from diffctl.bus import wire
from diffctl.cli import bus_common as bc
from diffctl.console import console
from diffctl.errors import ConfigError
from diffctl.interfaces import types


@click.group()
def node() -> None:
    """List nodes and what they publish, subscribe, serve and call.

    \b
    Example:
      diffctl node list
      diffctl node info /controller_manager
    """


@node.command("list")
def node_list() -> None:
    """List the nodes of the graph.

    \b
    Example:
      diffctl node list
    """
    for n in bc.graph().nodes():
        console.print(n, markup=False)


@node.command("info")
@click.argument("name")
def node_info(name: str) -> None:
    """Show NAME's subscribers, publishers, service servers and clients.

    \b
    Example:
      diffctl node info /robot_state_publisher
    """
    g = bc.graph()
    nodes = g.nodes()
    full = bc.resolve_name(g, name, nodes, "node")
    if full not in nodes:
        from diffctl.errors import suggest

        raise ConfigError(f"unknown node {full}{suggest(full, nodes)}", hint="`diffctl node list` shows them")
    ents = g.node_entities(full)
    console.print(full, markup=False)
    for title, kind in (
        ("Subscribers", wire.KIND_SUB),
        ("Publishers", wire.KIND_PUB),
        ("Service Servers", wire.KIND_SERVICE),
        ("Service Clients", wire.KIND_CLIENT),
    ):
        console.print(f"  {title}:", markup=False)
        for e in sorted({(e.topic, e.type) for e in ents if e.kind == kind}):
            console.print(f"    {e[0]}: {e[1]}", markup=False)


@click.group()
def service() -> None:
    """List and call services.

    \b
    Example:
      diffctl service list -t
      diffctl service call /controller_manager/list_controllers
    """


@service.command("list")
@click.option("-t", "--show-types", is_flag=True, help="Show each service's type.")
def service_list(show_types: bool) -> None:
    """List the services of the graph.

    \b
    Example:
      diffctl service list -t
    """
    for name, ts in bc.graph().services().items():
        console.print(f"{name} [{', '.join(ts)}]" if show_types else name, markup=False)


@service.command("type")
@click.argument("name")
def service_type(name: str) -> None:
    """Print a service's type.

    \b
    Example:
      diffctl service type /controller_manager/list_controllers
    """
    g = bc.graph()
    services = g.services()
    full = bc.resolve_name(g, name, list(services), "service")
    if full not in services:
        raise ConfigError(f"unknown service {full}", hint="`diffctl service list` shows the services that exist")
    for t in services[full]:
        console.print(t, markup=False)


@service.command("call")
@click.argument("name")
@click.argument("args", nargs=-1, metavar="[TYPE] [VALUES]")
@click.option("--timeout", type=float, default=5.0, show_default=True, help="Seconds to wait for the answer.")
def service_call(name: str, args: tuple[str, ...], timeout: float) -> None:
    """Call service NAME with VALUES (ROS YAML); TYPE may be left out when the graph knows it.

    \b
    Example:
      diffctl service call /controller_manager/list_controllers
      diffctl service call /controller_manager/load_controller controller_manager_msgs/srv/LoadController \\
          '{name: my_controller}'
    """
    if len(args) > 2:
        raise ConfigError(f"too many arguments: {' '.join(args)}", hint="expected [TYPE] [VALUES]")
    typename: str | None = None
    values_text: str | None = None
    for a in args:
        if typename is None and values_text is None and "/" in a and not a.lstrip().startswith("{") and ":" not in a:
            typename = a
        else:
            values_text = a
    values = bc.parse_values(values_text)
    g = bc.graph()
    services = g.services()
    full = bc.resolve_name(g, name, list(services), "service")
    if typename is None:
        ts = services.get(full)
        if not ts:
            raise ConfigError(
                f"unknown service {full} and no TYPE given", hint="`diffctl service list -t` shows services and types"
            )
        typename = ts[0]
    srv = types.check_service(typename)
    req = types.request(srv, values)
    n = bc.ToolNode(f"diffctl_service_call_{__import__('os').getpid()}")
    client = n.create_client(full, srv)
    if not client.wait_for_service(timeout):
        raise ConfigError(f"service {full} ({srv}) is not available", hint="`diffctl service list` shows them")
    console.print(f"requester: making request: {types.to_dict(req)}\n", markup=False)
    resp = client.call(req, timeout=timeout)
    console.print("response:", markup=False)
    console.print(yaml.safe_dump(types.to_dict(resp), sort_keys=False, default_flow_style=False).rstrip(), markup=False)
    n.close()


@click.group()
def interface() -> None:
    """Show message and service definitions.

    \b
    Example:
      diffctl interface show geometry_msgs/msg/TwistStamped
    """


@interface.command("show")
@click.argument("typename", metavar="TYPE")
def interface_show(typename: str) -> None:
    """Print the definition of a message or service type.

    \b
    Example:
      diffctl interface show controller_manager_msgs/srv/SwitchController
    """
    console.print(types.definition(typename).rstrip(), markup=False)


@interface.command("list")
def interface_list() -> None:
    """List every message and service type diffctl knows.

    \b
    Example:
      diffctl interface list
    """
    seen = set()
    for t in types.known_types():
        base = t.rsplit("_", 1)[0] if "/srv/" in t else t
        if "/srv/" in t and not t.endswith(("_Request", "_Response")):
            continue
        if base not in seen:
            seen.add(base)
            console.print(base, markup=False)
