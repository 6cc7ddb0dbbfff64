# Topic and service name validation as rcl does it, graph queries about a missing node, shutdown twice.
import json

import rclpy
from rclpy.node import Node
from rclpy.validate_topic_name import validate_topic_name

out = []


def obs(label, fn):
    try:
        out.append([label, "ok", fn()])
    except Exception as e:
        out.append([label, type(e).__name__, str(e)])


rclpy.init()

for name in ("", "a/", "a b", "1a", "a/1b", "{x", "a~b", "~x", "a//b", "{1}", "{a b}", "/a", "~", "{node}/x"):
    obs(repr(name), lambda name=name: validate_topic_name(name))
n = Node("x")
obs("sub names", lambda: n.get_subscriber_names_and_types_by_node("ghost", "/"))
obs("srv names", lambda: n.get_service_names_and_types_by_node("ghost", "/"))
obs("cli names", lambda: n.get_client_names_and_types_by_node("ghost", "/"))
rclpy.shutdown()
obs("shutdown twice", lambda: rclpy.get_default_context().shutdown())
c = rclpy.context.Context()
c.init()
c.shutdown()
obs("context shutdown twice", lambda: c.shutdown())
print(json.dumps(out))
