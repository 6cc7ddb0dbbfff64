"""`diffctl topic …`: list, echo, pub, hz, info, type — the `ros2 topic` counterpart over rmw_zenoh."""

from __future__ import annotations

import itertools
import math
import statistics
import sys
import threading
import time
from collections import deque
from typing import Any

import click
import yaml

from diffctl.bus import wire
from diffctl.cli import bus_common as bc
from diffctl.console import console, info, warn
from diffctl.errors import ConfigError
from diffctl.interfaces import types
from diffctl.signals import stop_on_signals


@click.group()
def topic() -> None:
    """Inspect and publish topics, as `ros2 topic` does.

    \b
    Example:
      diffctl topic list -t
      diffctl topic echo /diffbot_base_controller/odom --once
      diffctl topic pub cmd_vel '{twist: {linear: {x: 0.5}}}' --rate 10
    """


@topic.command("list")
@click.option("-t", "--show-types", is_flag=True, help="Show each topic's type.")
@click.option("-v", "--verbose", is_flag=True, help="List publishers and subscribers per topic.")
def list_(show_types: bool, verbose: bool) -> None:
    """List the topics of the graph.

    \b
    Example:
      diffctl topic list -t
    """
    g = bc.graph()
    topics = g.topics()
    if verbose:
        for title, fn, noun in (
            ("Published topics:", g.publishers, "publisher"),
            ("Subscribed topics:", g.subscribers, "subscriber"),
        ):
            console.print(title)
            for name, ts in topics.items():
                n = len(fn(name))
                if n:
                    console.print(f" * {name} [{', '.join(ts)}] {n} {noun}{'s' if n > 1 else ''}", markup=False)
            console.print("")
        return
    for name, ts in topics.items():
        console.print(f"{name} [{', '.join(ts)}]" if show_types else name, markup=False)


def _select(d: Any, field: str | None) -> Any:
    if not field:
        return d
    for part in field.split("."):
        if isinstance(d, dict) and part in d:
            d = d[part]
        else:
            valid = ", ".join(d) if isinstance(d, dict) else "(not a message)"
            raise ConfigError(f"--field {field!r}: no field {part!r}", hint=f"valid here: {valid}")
    return d


def _no_arr(d: Any, typename: str = "") -> Any:
    if isinstance(d, dict):
        return {k: _no_arr(v) for k, v in d.items()}
    if isinstance(d, list):
        return f"<sequence length: {len(d)}>"
    return d


def _yaml(d: Any) -> str:
    if not isinstance(d, (dict, list)):
        return yaml.safe_dump(d, default_flow_style=False).replace("\n...\n", "\n")
    return yaml.safe_dump(d, sort_keys=False, default_flow_style=False, width=1000)


@topic.command()
@click.argument("topic_name", metavar="TOPIC")
@click.argument("typename", metavar="[TYPE]", required=False)
@click.option("--once", is_flag=True, help="Print the first message and exit.")
@click.option("--field", default=None, help="Print only this field, e.g. twist.linear.")
@click.option("--no-arr", is_flag=True, help="Print array lengths instead of array contents.")
@click.option("--timeout", type=float, default=None, help="Give up after this many seconds without a message.")
def echo(
    topic_name: str, typename: str | None, once: bool, field: str | None, no_arr: bool, timeout: float | None
) -> None:
    """Print messages of TOPIC as YAML documents separated by ---.

    \b
    Example:
      diffctl topic echo /diffbot_base_controller/odom --field pose.pose.position
    """
    g = bc.graph()
    name = bc.resolve_name(g, topic_name, list(g.topics()))
    t = bc.wait_for_type(g, name, typename, timeout)
    node = bc.ToolNode(f"diffctl_echo_{_pid()}")
    stop = stop_on_signals()
    got = threading.Event()
    lock = threading.Lock()

    def on_msg(msg: Any) -> None:
        d = _select(types.to_dict(msg), field)
        if no_arr:
            d = _no_arr(d)
        with lock:
            if stop.is_set():
                return
            sys.stdout.write(_yaml(d) + "---\n")
            sys.stdout.flush()
            got.set()
            if once:
                stop.set()

    # As ros2 topic echo: depth 10, transient local when the publishers are (a late echo of /rosout shows its
    # recent lines, of /robot_description the one there is).
    node.create_subscription(name, t, on_msg, latched=bc.is_latched(g, name), depth=10)
    deadline = None if timeout is None else time.monotonic() + timeout
    while not stop.wait(0.05):
        if deadline and not got.is_set() and time.monotonic() > deadline:
            node.close()
            raise ConfigError(f"no message on {name} within {timeout:g} s")
    node.close()


def _pid() -> int:
    import os

    return os.getpid()


def _stamp_fields(msg: Any) -> list[Any]:
    """Header-like objects at the top level whose stamp should be filled ('zero stamp = now')."""
    out = []
    h = getattr(msg, "header", None)
    if h is not None and hasattr(h, "stamp"):
        out.append(h)
    return out


@topic.command()
@click.argument("topic_name", metavar="TOPIC")
@click.argument("args", nargs=-1, metavar="[TYPE] VALUES")
@click.option("-r", "--rate", type=float, default=None, help="Publishing rate in Hz (default 1).")
@click.option("-1", "--once", is_flag=True, help="Publish one message and exit.")
@click.option("-t", "--times", type=int, default=None, help="Publish this many messages and exit.")
@click.option(
    "-w",
    "--wait-matching-subscriptions",
    "wait_subs",
    type=int,
    default=None,
    help="Wait for this many subscribers before publishing (default 1 with --once/--times).",
)
def pub(
    topic_name: str, args: tuple[str, ...], rate: float | None, once: bool, times: int | None, wait_subs: int | None
) -> None:
    """Publish VALUES (ROS YAML) on TOPIC; TYPE may be left out when the graph knows the topic.

    A zero header stamp is filled with the current time (sim time when /clock runs).

    \b
    Example:
      diffctl topic pub cmd_vel '{twist: {linear: {x: 0.5}, angular: {z: 0.3}}}' --rate 10
      diffctl topic pub /chatter std_msgs/msg/String '{data: hello}' --once
    """
    if len(args) > 2:
        raise ConfigError(f"too many arguments: {' '.join(args)}", hint="expected [TYPE] VALUES (quote VALUES)")
    typename, values_text = (args[0], args[1]) if len(args) == 2 else (None, args[0] if args else None)
    if (
        typename is None
        and values_text is not None
        and not values_text.lstrip().startswith(("{", "-"))
        and "/" in values_text
        and ":" not in values_text
    ):
        typename, values_text = values_text, None  # `topic pub /x pkg/msg/T` with no values
    if rate is not None and not (math.isfinite(rate) and rate > 0):
        raise ConfigError(f"--rate {rate!r} must be a positive number of Hz")
    if times is not None and times < 1:
        raise ConfigError(f"--times {times} must be at least 1")
    values = bc.parse_values(values_text)
    g = bc.graph()
    name = bc.resolve_name(g, topic_name, list(g.topics()))
    if typename is None:
        typename = bc.publisher_type(g, name) or (g.topics().get(name) or [None])[0]
        if typename is None:
            raise ConfigError(f"the graph does not know {name}'s type", hint="pass TYPE, e.g. geometry_msgs/msg/Twist")
    t = types.check(typename)
    msg = types.new(t, values)  # validates every field before anything is published
    use_sim = bc.sim_time_running(g)
    node = bc.ToolNode(f"diffctl_pub_{_pid()}", use_sim_time=use_sim)
    publisher = node.create_publisher(name, t)
    fill = [h for h in _stamp_fields(msg) if h.stamp.sec == 0 and h.stamp.nanosec == 0]
    if fill:
        info(f"header.stamp is zero: filling it with the current {'sim' if use_sim else 'wall'} time")
    count = 1 if once else times
    if wait_subs is None and count is not None:
        wait_subs = 1
    stop = stop_on_signals()
    if wait_subs:
        deadline = time.monotonic() + 5.0
        while publisher.subscription_count < wait_subs and not stop.is_set():
            if time.monotonic() > deadline:
                warn(f"no subscriber on {name} after 5 s; publishing anyway")
                break
            time.sleep(0.02)
        time.sleep(0.05)  # let the new subscriber's Zenoh declaration settle
    period = 1.0 / (rate or 1.0)
    n = 0
    nxt = time.monotonic()
    while not stop.is_set():
        if use_sim and fill:
            deadline = time.monotonic() + 2.0
            while not node.now_ns() and time.monotonic() < deadline:
                time.sleep(0.01)
        for h in fill:
            now = types.time_msg(node.now_ns())
            h.stamp.sec, h.stamp.nanosec = now.sec, now.nanosec
        publisher.publish(msg)
        n += 1
        if n == 1 or count is not None:
            console.print(
                f"publisher: beginning loop\npublishing #{n}: {types.to_dict(msg)}" if n == 1 else f"publishing #{n}",
                markup=False,
                highlight=False,
            )
        if count is not None and n >= count:
            break
        nxt += period
        stop.wait(max(0.0, nxt - time.monotonic()))
    time.sleep(0.1)  # give the last sample time to leave before the session closes
    node.close()


@topic.command()
@click.argument("topic_name", metavar="TOPIC")
@click.option("-w", "--window", type=int, default=10000, help="Number of intervals to average over.")
@click.option("--count", "reports", type=int, default=None, help="Exit after this many reports.")
def hz(topic_name: str, window: int, reports: int | None) -> None:
    """Print the publishing rate of TOPIC every second: average, min, max, std dev.

    \b
    Example:
      diffctl topic hz /scan
    """
    if window < 1:
        raise ConfigError(f"--window {window} must be at least 1")
    g = bc.graph()
    name = bc.resolve_name(g, topic_name, list(g.topics()))
    t = bc.wait_for_type(g, name, None, None)
    node = bc.ToolNode(f"diffctl_hz_{_pid()}")
    stamps: deque[float] = deque(maxlen=window + 1)
    lock = threading.Lock()

    def on_msg(_raw: bytes) -> None:
        with lock:
            stamps.append(time.monotonic())

    node.create_subscription(name, t, on_msg, raw=True)
    stop = stop_on_signals()
    done = 0
    while not stop.wait(1.0):
        with lock:
            ts = list(stamps)
        if len(ts) < 2:
            console.print("no new messages", markup=False)
            continue
        d = [b - a for a, b in itertools.pairwise(ts)]
        mean = statistics.fmean(d)
        sd = statistics.pstdev(d) if len(d) > 1 else 0.0
        console.print(
            f"average rate: {1.0 / mean:.3f}\n\tmin: {min(d):.3f}s max: {max(d):.3f}s "
            f"std dev: {sd:.5f}s window: {len(d)}",
            markup=False,
        )
        done += 1
        if reports is not None and done >= reports:
            break
    node.close()


@topic.command("info")
@click.argument("topic_name", metavar="TOPIC")
@click.option("-v", "--verbose", is_flag=True, help="List every endpoint with node, type, hash and QoS.")
def info_(topic_name: str, verbose: bool) -> None:
    """Show TOPIC's type and its publishers and subscribers; warn when their types differ.

    \b
    Example:
      diffctl topic info /diffbot_base_controller/cmd_vel -v
    """
    g = bc.graph()
    name = bc.resolve_name(g, topic_name, list(g.topics()))
    ts = g.topics().get(name)
    if not ts:
        raise ConfigError(f"unknown topic {name}", hint="`diffctl topic list` shows the topics that exist")
    pubs, subs = g.publishers(name), g.subscribers(name)
    console.print(f"Type: {', '.join(ts)}\nPublisher count: {len(pubs)}\nSubscription count: {len(subs)}", markup=False)
    if verbose:
        for title, ents in (("Publishers", pubs), ("Subscriptions", subs)):
            console.print(f"\n{title}:", markup=False)
            for e in ents:
                console.print(
                    f"Node name: {e.node}\nNode namespace: {e.namespace}\nTopic type: {e.type}\n"
                    f"Topic type hash: {e.type_hash}\nEndpoint type: "
                    f"{'PUBLISHER' if e in pubs else 'SUBSCRIPTION'}\nGID: {e.gid.hex('.')}\n"
                    f"QoS profile:\n{qos_text(e.qos_profile)}\n",
                    markup=False,
                )
    if len(ts) > 1:
        detail = "; ".join(bc.fmt_endpoint(e) for e in pubs + subs)
        warn(f"type mismatch on {name}: {' vs '.join(ts)} — these endpoints never exchange messages ({detail})")


def qos_text(q: wire.QoS | None) -> str:
    """A QoS profile as `ros2 topic info -v` prints it."""
    if q is None:
        return "  (unknown)"

    def duration(ns: int | None) -> str:
        return "Infinite" if ns is None else f"{ns} nanoseconds"

    history = "KEEP_ALL" if q.keep_all else f"KEEP_LAST ({q.depth})"
    return (
        f"  Reliability: {'RELIABLE' if q.reliable else 'BEST_EFFORT'}\n  History (Depth): {history}\n"
        f"  Durability: {'TRANSIENT_LOCAL' if q.transient_local else 'VOLATILE'}\n"
        f"  Lifespan: {duration(q.lifespan_ns)}\n  Deadline: {duration(q.deadline_ns)}\n"
        "  Liveliness: AUTOMATIC\n  Liveliness lease duration: Infinite"
    )


@topic.command("type")
@click.argument("topic_name", metavar="TOPIC")
def type_(topic_name: str) -> None:
    """Print TOPIC's type.

    \b
    Example:
      diffctl topic type /clock
    """
    g = bc.graph()
    name = bc.resolve_name(g, topic_name, list(g.topics()))
    ts = g.topics().get(name)
    if not ts:
        raise ConfigError(f"unknown topic {name}", hint="`diffctl topic list` shows the topics that exist")
    for t in ts:
        console.print(t, markup=False)
