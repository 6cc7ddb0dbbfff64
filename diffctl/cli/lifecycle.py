"""`diffctl lifecycle nodes|get|set|list`: ros2lifecycle's verbs over a managed node's lifecycle services.

Same arguments and printouts as `ros2 lifecycle` (`unconfigured [1]`, `Transitioning successful`, the
transition list with Start/Goal), so `ros2 lifecycle …` in a launch file or a script reaches it.
"""

from __future__ import annotations

import os
import sys
from typing import Any

import click

from diffctl.cli import bus_common as bc
from diffctl.errors import ConfigError
from diffctl.interfaces import types

GET_STATE = "lifecycle_msgs/srv/GetState"


@click.group()
def lifecycle() -> None:
    """Inspect and drive managed (lifecycle) nodes, as `ros2 lifecycle` does.

    \b
    Example:
      diffctl lifecycle nodes
      diffctl lifecycle get /lc_talker
      diffctl lifecycle set /lc_talker configure
    """


def _managed_nodes() -> list[str]:
    """Nodes serving `<node>/get_state` of lifecycle_msgs/srv/GetState (how ros2lifecycle finds them)."""
    services = bc.graph().services()
    suffix = "/get_state"
    nodes = {name[: -len(suffix)] for name, ts in services.items() if name.endswith(suffix) and GET_STATE in ts}
    return sorted(n for n in nodes if n)


def _call(node_name: str, service: str, typename: str, values: dict[str, Any], timeout_s: float = 5.0) -> dict:
    srv = types.check_service(typename)
    n = bc.ToolNode(f"diffctl_lifecycle_{os.getpid()}")
    try:
        client = n.create_client(f"{node_name}/{service}", srv)
        if not client.wait_for_service(timeout_s):
            raise ConfigError(f"service {node_name}/{service} is not available")
        return types.to_dict(client.call(types.request(srv, values), timeout=timeout_s))
    finally:
        n.close()


def _existing(node_name: str) -> str:
    full = "/" + node_name.lstrip("/")
    if full not in _managed_nodes():
        click.echo("Node not found", err=True)
        sys.exit(1)
    return full


@lifecycle.command("nodes")
def lifecycle_nodes() -> None:
    """List the nodes that have lifecycle services."""
    for name in _managed_nodes():
        click.echo(name)


@lifecycle.command("get")
@click.argument("node_name", required=False)
def lifecycle_get(node_name: str | None) -> None:
    """Print the current state of NODE_NAME (of every managed node without one)."""
    names = [_existing(node_name)] if node_name else _managed_nodes()
    for name in names:
        state = _call(name, "get_state", GET_STATE, {})["current_state"]
        prefix = f"{name}: " if node_name is None else ""
        click.echo(f"{prefix}{state['label']} [{state['id']}]")


@lifecycle.command("list")
@click.argument("node_name")
@click.option("-a", "--all", "all_", is_flag=True, help="Every transition of the state machine, not only current ones.")
def lifecycle_list(node_name: str, all_: bool) -> None:
    """List the transitions NODE_NAME can take now (all of them with --all)."""
    name = _existing(node_name)
    service = "get_transition_graph" if all_ else "get_available_transitions"
    answer = _call(name, service, "lifecycle_msgs/srv/GetAvailableTransitions", {})
    for t in answer["available_transitions"]:
        click.echo(
            f"- {t['transition']['label']} [{t['transition']['id']}]\n"
            f"\tStart: {t['start_state']['label']}\n\tGoal: {t['goal_state']['label']}"
        )


@lifecycle.command("set")
@click.argument("node_name")
@click.argument("transition")
def lifecycle_set(node_name: str, transition: str) -> None:
    """Trigger TRANSITION (its label, e.g. configure, or its id) on NODE_NAME."""
    name = _existing(node_name)
    available = _call(name, "get_available_transitions", "lifecycle_msgs/srv/GetAvailableTransitions", {})
    choices = [t["transition"] for t in available["available_transitions"]]
    chosen = next((t for t in choices if t["label"] == transition), None) or next(
        (t for t in choices if str(t["id"]) == transition), None
    )
    if chosen is None:
        click.echo(
            "Unknown transition requested, available ones are:"
            + "".join(f"\n- {t['label']} [{t['id']}]" for t in choices),
            err=True,
        )
        sys.exit(1)
    answer = _call(name, "change_state", "lifecycle_msgs/srv/ChangeState", {"transition": chosen})
    if answer["success"]:
        click.echo("Transitioning successful")
    else:
        click.echo("Transitioning failed", err=True)
        sys.exit(1)
