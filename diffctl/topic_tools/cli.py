"""`diffctl topic-tools relay|throttle|drop|delay|mux|demux|relay_field …`: the executables of package
topic_tools, with their command lines (`Node(package='topic_tools', executable='relay', …)`,
`diffctl run topic_tools throttle messages /scan 1.0`)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import click

from diffctl.errors import ConfigError

_PASS_THROUGH = {"ignore_unknown_options": True, "allow_interspersed_args": False, "help_option_names": []}
USAGE = "Usage: ros2 run topic_tools {name} <{first}> <{many}1> [{many}2...]"


def _number(text: str, cast: Callable[[str], Any], what: str) -> Any:
    try:
        return cast(text)
    except ValueError:
        raise ConfigError(f"{what} must be a {'whole ' if cast is int else ''}number, got {text!r}") from None


def _spin(name: str, build: Callable[[Any], Any], overrides: dict[str, Any]) -> int:
    from diffctl.client import component
    from diffctl.client.node import Node
    from diffctl.client.parameter import Parameter

    def make() -> Node:
        node = Node(name, parameter_overrides=[Parameter(k, value=v) for k, v in overrides.items()])
        build(node)
        return node

    return component.run(make)


@click.group("topic-tools")
def topic_tools() -> None:
    """topic_tools' nodes: relay, throttle, drop, delay, mux, demux, relay_field (any message type).

    \b
    Example:
      diffctl topic-tools relay /scan /scan_relay
      diffctl topic-tools throttle messages /camera/image_raw 2.0
      diffctl topic-tools mux /cmd_vel /cmd_vel_auto /cmd_vel_joy
    """


@topic_tools.command("relay", context_settings=_PASS_THROUGH)
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def relay(args: tuple[str, ...]) -> None:
    """relay <intopic> [outtopic]: republish every message (default outtopic: <intopic>_relay)."""
    from diffctl.topic_tools import tools

    o = dict(zip(("input_topic", "output_topic"), args, strict=False))
    raise SystemExit(_spin("relay", tools.relay, o))


@topic_tools.command("throttle", context_settings=_PASS_THROUGH)
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def throttle(args: tuple[str, ...]) -> None:
    """throttle messages <intopic> <msgs_per_sec> [outtopic] | throttle bytes <intopic> <bytes_per_sec> <window>
    [outtopic]."""
    from diffctl.topic_tools import tools

    if not args:
        click.echo("Throttle type is missing.")
        raise SystemExit(0)
    o: dict[str, Any] = {}
    if args[0] == "messages":
        o["throttle_type"] = "messages"
        if len(args) >= 3:
            o["input_topic"], o["msgs_per_sec"] = args[1], _number(args[2], float, "msgs_per_sec")
            if len(args) >= 4:
                o["output_topic"] = args[3]
    elif args[0] == "bytes":
        o["throttle_type"] = "bytes"
        if len(args) >= 4:
            o["input_topic"] = args[1]
            o["bytes_per_sec"] = _number(args[2], int, "bytes_per_sec")
            o["window"] = _number(args[3], float, "window")
            if len(args) >= 5:
                o["output_topic"] = args[4]
    raise SystemExit(_spin("throttle", tools.throttle, o))


@topic_tools.command("drop", context_settings=_PASS_THROUGH)
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def drop(args: tuple[str, ...]) -> None:
    """drop <intopic> <X> <Y> [outtopic]: drop X out of every Y messages (default outtopic: <intopic>_drop)."""
    from diffctl.topic_tools import tools

    o: dict[str, Any] = {}
    if len(args) >= 3:
        o = {"input_topic": args[0], "X": _number(args[1], int, "X"), "Y": _number(args[2], int, "Y")}
        if len(args) >= 4:
            o["output_topic"] = args[3]
    raise SystemExit(_spin("drop", tools.drop, o))


@topic_tools.command("delay", context_settings=_PASS_THROUGH)
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def delay(args: tuple[str, ...]) -> None:
    """delay <intopic> <delay> [outtopic]: republish each message `delay` seconds later."""
    from diffctl.topic_tools import tools

    o: dict[str, Any] = dict(zip(("input_topic",), args[:1], strict=False))
    if len(args) >= 2:
        o["delay"] = _number(args[1], float, "delay")
        if len(args) >= 3:
            o["output_topic"] = args[2]
    raise SystemExit(_spin("delay", tools.delay, o))


def _switch(kind: str, args: tuple[str, ...]) -> int:
    from diffctl.topic_tools.mux import Switch

    if len(args) < 2:
        first, many = ("outtopic", "intopic") if kind == "mux" else ("intopic", "outtopic")
        click.echo(f"[ERROR] [{kind}]: Incorect number of arguments. "
                   + USAGE.format(name=kind, first=first, many=many), err=True)
        return 1
    o = {"output_topic": args[0], "input_topics": list(args[1:])} if kind == "mux" else \
        {"input_topic": args[0], "output_topics": list(args[1:])}
    return _spin(kind, lambda node: Switch(node, kind), o)


@topic_tools.command("mux", context_settings=_PASS_THROUGH)
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def mux(args: tuple[str, ...]) -> None:
    """mux <outtopic> <intopic1> [intopic2...]: one input at a time to outtopic (~/select to switch)."""
    raise SystemExit(_switch("mux", args))


@topic_tools.command("demux", context_settings=_PASS_THROUGH)
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def demux(args: tuple[str, ...]) -> None:
    """demux <intopic> <outtopic1> [outtopic2...]: intopic to one output at a time (~/select to switch)."""
    raise SystemExit(_switch("demux", args))


@topic_tools.command("relay_field", context_settings=_PASS_THROUGH)
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
def relay_field(args: tuple[str, ...]) -> None:
    """relay_field <input> <output topic> <output type> <expression on m>."""
    from diffctl.client import component
    from diffctl.client.node import Node
    from diffctl.topic_tools.relay_field import parser, start

    parsed = parser().parse_args(list(args))

    def stopped(e: BaseException) -> None:
        if isinstance(e, KeyboardInterrupt):
            print("relay_field stopped cleanly")

    raise SystemExit(component.run(lambda: start(Node, parsed), on_stop=stopped))
