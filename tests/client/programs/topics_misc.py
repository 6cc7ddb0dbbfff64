# Topics beyond plain callbacks, the graph, names, logging and init/shutdown as a user observes them.
import json
import time

import rclpy
from rcl_interfaces.msg import Log
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from rclpy.serialization import deserialize_message, serialize_message
from rclpy.wait_for_message import wait_for_message
from std_msgs.msg import Int32, String

out = []


def obs(label, fn):
    try:
        out.append([label, "ok", fn()])
    except Exception as e:
        out.append([label, type(e).__name__, str(e)])


obs("node before init", lambda: Node("too_early") and "created")
obs("ok before init", lambda: rclpy.ok())
rclpy.init()
obs("init twice", lambda: rclpy.init())
obs("ok", lambda: rclpy.ok())
node = Node("misc_demo", namespace="demo_ns")
obs("names", lambda: [node.get_name(), node.get_namespace(), node.get_fully_qualified_name(),
                      node.get_logger().name])
obs("bad node name", lambda: Node("bad-name"))
obs("bad namespace", lambda: Node("fine", namespace="/bad//ns"))
obs("bad topic", lambda: node.create_publisher(String, "bad topic", 10))
obs("qos as string", lambda: node.create_publisher(String, "x", "10"))
obs("negative depth", lambda: node.create_publisher(String, "x", -1))
obs("resolve", lambda: [node.resolve_topic_name("chatter"), node.resolve_topic_name("~/private"),
                        node.resolve_topic_name("/abs")])
ex = SingleThreadedExecutor()
ex.add_node(node)


def spin_for(seconds):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        ex.spin_once(timeout_sec=0.05)


raw, info, typed = [], [], []
pub = node.create_publisher(String, "chatter", QoSProfile(depth=7, reliability=ReliabilityPolicy.RELIABLE))
node.create_subscription(String, "chatter", raw.append, 10, raw=True)
node.create_subscription(String, "chatter", lambda m, i: info.append(sorted(i)), 10)
node.create_subscription(String, "chatter", lambda m, extra=None: typed.append(type(m).__name__), 10)
end = time.monotonic() + 5
while pub.get_subscription_count() < 3 and time.monotonic() < end:
    spin_for(0.05)
obs("subscription count", lambda: pub.get_subscription_count())
pub.publish(String(data="hi"))
obs("publish wrong type", lambda: pub.publish(Int32(data=1)))
pub.publish(serialize_message(String(data="as bytes")))
spin_for(0.5)
obs("raw", lambda: [isinstance(raw[0], bytes), raw[0] == serialize_message(String(data="hi")),
                    deserialize_message(raw[1], String).data])
obs("message info keys", lambda: info[0])
obs("callback with a defaulted second parameter gets the message only", lambda: typed)
obs("topic name", lambda: [pub.topic_name, node.count_publishers("chatter"), node.count_subscribers("chatter"),
                           node.count_publishers("/nobody")])
infos = node.get_publishers_info_by_topic("chatter")
obs("publishers info", lambda: [[i.node_name, i.node_namespace, i.topic_type, i.endpoint_type.name,
                                 i.qos_profile.reliability.name, i.qos_profile.durability.name,
                                 len(i.endpoint_gid) > 0] for i in infos])
obs("topics", lambda: [t for t in node.get_topic_names_and_types() if t[0].startswith("/demo_ns")])
obs("services of the node", lambda: sorted(
    s for s, _ in node.get_service_names_and_types_by_node("misc_demo", "/demo_ns")))
obs("nodes", lambda: ("misc_demo", "/demo_ns") in node.get_node_names_and_namespaces())
obs("node names", lambda: "misc_demo" in node.get_node_names())

late = node.create_publisher(String, "later", QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL))
late.publish(String(data="kept"))
obs("wait_for_message", lambda: (lambda r: [r[0], r[1].data])(wait_for_message(
    String, node, "later", qos_profile=QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL),
    time_to_wait=5)))
obs("wait_for_message timeout", lambda: list(wait_for_message(String, node, "silent", time_to_wait=0.3)))

logs = []
node.create_subscription(Log, "/rosout", lambda m: logs.append(m),
                         QoSProfile(depth=100, durability=DurabilityPolicy.TRANSIENT_LOCAL))
spin_for(0.3)
logger = node.get_logger()
obs("log returns", lambda: [logger.info("to rosout"), logger.debug("hidden"), logger.warning("warned")])
obs("effective level", lambda: [logger.get_effective_level().name, logger.is_enabled_for(10)])
spin_for(1.0)
obs("rosout", lambda: [[m.level, m.name, m.msg, m.function] for m in logs if m.name == "demo_ns.misc_demo"])
child = logger.get_child("child")
obs("child logger", lambda: [child.name, child.info("from the child")])
obs("log non-str", lambda: logger.info(42))
out[-1][2] = out[-1][2].splitlines()[0]
# Taking outside any executor through the subscription's handle (custom executors and recorders do)


def take_by_handle():
    sub = node.create_subscription(String, "handle_take", lambda m: None, 5)
    pub = node.create_publisher(String, "handle_take", 5)
    with sub.handle:
        seen = [sub.handle.take_message(sub.msg_type, False)]
    deadline = time.monotonic() + 5
    while pub.get_subscription_count() < 1 and time.monotonic() < deadline:
        time.sleep(0.01)
    pub.publish(String(data="first"))
    pub.publish(String(data="second"))
    taken = []
    while len(taken) < 2 and time.monotonic() < deadline:
        with sub.handle:
            got = sub.handle.take_message(sub.msg_type, len(taken) == 1)
        if got is None:
            time.sleep(0.01)
            continue
        msg, info = got
        taken.append([msg.data if len(taken) == 0 else msg[:4].hex(), sorted(info),
                      info["publication_sequence_number"] > 0, info["source_timestamp"] > 0])
    node.destroy_subscription(sub)
    node.destroy_publisher(pub)
    return [*seen, *taken]


obs("take by handle", take_by_handle)
# The root logger (rclpy.logging._root_logger, which packages log through): its level is every unset logger's,
# UNSET included (everything passes); a call site may not change its filter's options between calls.
root = rclpy.logging._root_logger


def root_levels():
    seen = []
    for level in (rclpy.logging.LoggingSeverity.UNSET, rclpy.logging.LoggingSeverity.WARN):
        root.set_level(level)
        seen.append([root.get_effective_level().name, rclpy.logging.get_logger_level("").name,
                     rclpy.logging.get_logger_effective_level("some.unset.child").name,
                     root.debug("root debug line")])
    rclpy.logging.set_logger_level("", rclpy.logging.LoggingSeverity.INFO)
    return [*seen, root.get_effective_level().name, root.name]


def changed_throttle():
    return [root.info("throttled root line", throttle_duration_sec=d) for d in (1, 2)]


obs("root logger", root_levels)
obs("filter options changed", changed_throttle)
node.destroy_node()
obs("shutdown", lambda: rclpy.shutdown())
obs("ok after", lambda: rclpy.ok())
obs("try_shutdown again", lambda: rclpy.try_shutdown())
print(json.dumps(out))
