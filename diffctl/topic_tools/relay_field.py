"""relay_field: republish fields of one topic's messages as another type, from a YAML template whose string
values are Python expressions on the input message `m` (topic_tools' relay_field.py, its command line)."""

from __future__ import annotations

import argparse
import copy
import os
from typing import Any

import yaml

from diffctl.client.qos import (
    DurabilityPolicy,
    HistoryPolicy,
    QoSPresetProfiles,
    ReliabilityPolicy,
)


def evaluate(template: Any, m: Any) -> Any:
    """The template with each string (or bytes) value replaced by its value as an expression on `m` where it
    is one; strings that are not expressions (a NameError or SyntaxError) stay as they are."""
    out = copy.deepcopy(template)
    for k, v in out.items():
        if isinstance(v, dict):
            out[k] = evaluate(v, m)
        elif isinstance(v, (str, bytes)):
            try:
                out[k] = eval(v, None, {"m": m})
            except (NameError, SyntaxError):
                pass
    return out


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="relay_field", formatter_class=argparse.RawTextHelpFormatter,
        description="Allows to relay field data from one topic to another.\n\nUsage:\n\tros2 run topic_tools "
                    "relay_field <input> <output topic> <output type> <expression on m>\n\nExample:\n\tros2 run "
                    "topic_tools relay_field /chatter /header std_msgs/Header \"{stamp: {sec: 0, nanosec: 0}, "
                    "frame_id: m.data}\"")
    p.add_argument("input", help="Input topic or topic field.")
    p.add_argument("output_topic", help="Output topic.")
    p.add_argument("output_type", help="Output topic type.")
    p.add_argument("expression", help="Python expression to apply on the input message 'm'.")
    p.add_argument("--wait-for-start", action="store_true", help="Wait for input messages.")
    p.add_argument("--qos-profile", choices=QoSPresetProfiles.short_keys(),
                   help="Quality of service preset profile to subscribe with (default: sensor_data)")
    p.add_argument("--qos-depth", metavar="N", type=int,
                   help="Queue size setting to subscribe with (overrides depth value of --qos-profile option)")
    p.add_argument("--qos-history", choices=[k.lower() for k in HistoryPolicy.__members__],
                   help="History of samples setting to subscribe with (overrides history value of --qos-profile "
                        "option, default: keep_last)")
    p.add_argument("--qos-reliability", choices=[k.lower() for k in ReliabilityPolicy.__members__],
                   help="Quality of service reliability setting to subscribe with (overrides reliability value of "
                        "--qos-profile option, default: Automatically match existing publishers )")
    p.add_argument("--qos-durability", choices=[k.lower() for k in DurabilityPolicy.__members__],
                   help="Quality of service durability setting to subscribe with (overrides durability value of "
                        "--qos-profile option, default: Automatically match existing publishers )")
    return p


def _qos(args: argparse.Namespace, node: Any, topic: str) -> Any:
    """The QoS to use: from the options when any is given, else sensor_data matched to the publishers."""
    profile = copy.copy(QoSPresetProfiles.get_from_short_key(args.qos_profile or "sensor_data"))
    given = (args.qos_profile, args.qos_reliability, args.qos_durability, args.qos_depth, args.qos_history)
    if any(v is not None for v in given):
        if args.qos_reliability is not None:
            profile.reliability = ReliabilityPolicy[args.qos_reliability.upper()]
        if args.qos_durability is not None:
            profile.durability = DurabilityPolicy[args.qos_durability.upper()]
        if args.qos_history is not None:
            profile.history = HistoryPolicy[args.qos_history.upper()]
        if args.qos_depth is not None:
            profile.depth = args.qos_depth
        return profile
    infos = node.get_publishers_info_by_topic(topic)
    if not infos:
        return profile
    reliable = sum(1 for i in infos if i.qos_profile.reliability == ReliabilityPolicy.RELIABLE)
    latched = sum(1 for i in infos if i.qos_profile.durability == DurabilityPolicy.TRANSIENT_LOCAL)
    if reliable == len(infos):
        profile.reliability = ReliabilityPolicy.RELIABLE
    else:
        if reliable:
            print("Some, but not all, publishers are offering QoSReliabilityPolicy.RELIABLE. Falling back to "
                  "QoSReliabilityPolicy.BEST_EFFORT as it will connect to all publishers")
        profile.reliability = ReliabilityPolicy.BEST_EFFORT
    if latched == len(infos):
        profile.durability = DurabilityPolicy.TRANSIENT_LOCAL
    else:
        if latched:
            print("Some, but not all, publishers are offering QoSDurabilityPolicy.TRANSIENT_LOCAL. Falling back to "
                  "QoSDurabilityPolicy.VOLATILE as it will connect to all publishers")
        profile.durability = DurabilityPolicy.VOLATILE
    return profile


def _input_type(node: Any, topic: str, wait: bool) -> str | None:
    import time

    while True:
        types = {i.topic_type for i in node.get_publishers_info_by_topic(topic)}
        if types or not wait:
            return next(iter(sorted(types)), None)
        time.sleep(0.1)


def start(node_factory: Any, args: argparse.Namespace) -> Any:
    """Build the node; raises RuntimeError for an input topic nobody publishes (as upstream)."""
    from diffctl.interfaces import get_interface
    from diffctl.interfaces.runtime.set_message import set_message_fields

    node = node_factory(f"relay_field_{os.getpid()}")
    template = yaml.safe_load(args.expression)
    topic = args.input if args.input.startswith("/") else node.get_namespace().rstrip("/") + "/" + args.input
    type_name = _input_type(node, topic, args.wait_for_start)
    if type_name is None:
        raise RuntimeError(f"ERROR: Wrong input topic: {topic}")
    output_cls = get_interface(args.output_type)
    qos = _qos(args, node, topic)
    pub = node.create_publisher(output_cls, args.output_topic, qos)

    def callback(m: Any) -> None:
        try:
            values = evaluate(template, m)
        except AttributeError as e:
            raise RuntimeError(f"Invalid field: {e}") from e
        out = output_cls()
        stamps = set_message_fields(out, values, expand_header_auto=True, expand_time_now=True)
        now = node.get_clock().now().to_msg()
        for setter in stamps:
            setter(now)
        pub.publish(out)

    node.create_subscription(get_interface(type_name), topic, callback, qos)
    return node
