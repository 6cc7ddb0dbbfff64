# Names as rcl checks, expands and resolves them, and the exceptions rclpy raises for them: the validators,
# expand_topic_name, what create_* and the graph queries do with a bad name, type and callback checks, graph
# queries about a missing node, shutdown twice.
import json

import rclpy
from rclpy.expand_topic_name import expand_topic_name
from rclpy.node import Node
from rclpy.validate_full_topic_name import validate_full_topic_name
from rclpy.validate_namespace import validate_namespace
from rclpy.validate_node_name import validate_node_name
from rclpy.validate_topic_name import validate_topic_name
from std_msgs.msg import String
from std_srvs.srv import SetBool

out = []


def obs(label, fn):
    try:
        out.append([label, "ok", fn()])
    except Exception as e:
        out.append([label, type(e).__name__, str(e)])


def only_type(label, fn):  # pybind11's own TypeError texts name memory addresses
    try:
        fn()
        out.append([label, "ok"])
    except Exception as e:
        out.append([label, type(e).__name__])


rclpy.init()

NAMES = ("", "a/", "a b", "1a", "a/1b", "{x", "a~b", "~x", "~xy", "~/x", "a//b", "/a//b", "{1}", "{a b}", "{a/b}",
         "{a{b}}", "a}", "/a", "~", "{node}/x", "{ns}/x", "{namespace}/{node}", "{foo}/x", "{}", "/", "//", "a__b",
         "_a", "x" * 250, "/" + "x" * 250, "/a/" + "b" * 244)
for name in NAMES:
    obs(f"validate {name!r}", lambda name=name: validate_topic_name(name))
    obs(f"validate full {name!r}", lambda name=name: validate_full_topic_name(name, is_service=True))
    obs(f"validate ns {name!r}", lambda name=name: validate_namespace(name))
    obs(f"validate node {name!r}", lambda name=name: validate_node_name(name))
    obs(f"expand {name!r}", lambda name=name: [expand_topic_name(name, "talker", "/ns"),
                                                 expand_topic_name(name, "talker", "/")])
obs("validate node too long", lambda: validate_node_name("n" * 256))
obs("expand bad node", lambda: expand_topic_name("x", "bad name", "/ns"))
obs("expand relative ns", lambda: expand_topic_name("x", "n", "ns"))
obs("expand empty ns", lambda: expand_topic_name("x", "n", ""))
obs("expand bad topic before bad node", lambda: expand_topic_name("a b", "bad name", ""))

n = Node("probe", namespace="/ns")
for name in ("a//b", "/a//b", "a b", "1a", "{foo}/x", "~/a//b", "{node}//x", "a/", "~x"):
    obs(f"publisher {name!r}", lambda name=name: n.create_publisher(String, name, 10).topic_name)
    obs(f"subscription {name!r}", lambda name=name: n.create_subscription(String, name, lambda m: None, 10).topic_name)
    obs(f"client {name!r}", lambda name=name: n.create_client(SetBool, name).srv_name)
    obs(f"service {name!r}", lambda name=name: n.create_service(SetBool, name, lambda a, b: b).srv_name)
    obs(f"resolve {name!r}", lambda name=name: [n.resolve_topic_name(name),
                                                  n.resolve_service_name(name, only_expand=True)])
    # the node's own endpoints just made are counted at once, as rclpy's graph knows its own
    obs(f"count {name!r}", lambda name=name: [n.count_publishers(name), n.count_subscribers(name)])
    obs(f"count services {name!r}", lambda name=name: [n.count_clients(name), n.count_services(name)])
    obs(f"info {name!r}", lambda name=name: [len(n.get_publishers_info_by_topic(name)),
                                             len(n.get_subscriptions_info_by_topic(name))])
obs("publisher None", lambda: n.create_publisher(String, None, 10))
only_type("publisher int", lambda: n.create_publisher(String, 5, 10))
for label, node_name, ns in (("bad name", "a b", "/"), ("bad namespace", "ok", "/a b"),
                             ("relative namespace", "ok", "ns"), ("empty name", "", "/")):
    obs(f"names of a node by {label}", lambda a=node_name, b=ns: n.get_publisher_names_and_types_by_node(a, b))
    obs(f"services of a node by {label}", lambda a=node_name, b=ns: n.get_client_names_and_types_by_node(a, b))
obs("sub names", lambda: n.get_subscriber_names_and_types_by_node("ghost", "/"))
obs("srv names", lambda: n.get_service_names_and_types_by_node("ghost", "/"))
obs("cli names", lambda: n.get_client_names_and_types_by_node("ghost", "/"))

for label, node_name, ns in (("bad", "bad name", None), ("double slash ns", "ok", "/a//b"),
                             ("trailing slash ns", "ok", "/a/"), ("empty", "", None), ("digit", "1x", None),
                             ("digit ns", "ok", "/1a"),
                             ("long", "x" * 256, None), ("relative ns", "ok", "rel/ns"), ("empty ns", "ok", "")):
    obs(f"node {label}", lambda a=node_name, b=ns: Node(a, namespace=b).get_fully_qualified_name())
obs("node None", lambda: Node(None))
only_type("node int", lambda: Node(5))
only_type("node namespace int", lambda: Node("x", namespace=5))

obs("message type str", lambda: n.create_publisher("std_msgs/msg/String", "t", 10))
obs("message type None", lambda: n.create_subscription(None, "t", lambda m: None, 10))
obs("service type as message", lambda: n.create_publisher(SetBool, "t", 10))
obs("message type as service", lambda: n.create_client(String, "s"))
obs("service type str", lambda: n.create_service("std_srvs/srv/SetBool", "s", lambda a, b: b))
obs("callback None", lambda: n.create_subscription(String, "t", None, 10))
obs("callback of three", lambda: n.create_subscription(String, "t", lambda a, b, c: None, 10))
obs("callback of two", lambda: n.create_subscription(String, "t", lambda a, b: None, 10).topic_name)
obs("destroy None", lambda: [n.destroy_publisher(None), n.destroy_subscription(None)])

rclpy.shutdown()
obs("shutdown twice", lambda: rclpy.get_default_context().shutdown())
c = rclpy.context.Context()
c.init()
c.shutdown()
obs("context shutdown twice", lambda: c.shutdown())
print(json.dumps(out))
