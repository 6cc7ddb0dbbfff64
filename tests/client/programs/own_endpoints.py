# A node's own endpoints in the graph queries right after create_* and gone right after destroy_*, with no
# spin in between: rclpy's graph knows the process's own entities at once (the middleware's echo comes later).
import json

import rclpy
from rclpy.node import Node
from std_msgs.msg import String
from std_srvs.srv import SetBool

out = []
rclpy.init()
n = Node("counter", namespace="/own")
m = Node("other", namespace="/own")
n.create_publisher(String, "chatter", 10)
out.append(["after pub", n.count_publishers("chatter"), m.count_publishers("/own/chatter"),
            n.get_publisher_names_and_types_by_node("counter", "/own")])
s = m.create_subscription(String, "/own/chatter", lambda msg: None, 10)
out.append(["after sub", n.count_subscribers("chatter"),
            m.get_subscriber_names_and_types_by_node("other", "/own")])
n.create_service(SetBool, "flip", lambda a, b: b)
c = m.create_client(SetBool, "/own/flip")
out.append(["after srv", n.count_services("flip"), n.count_clients("flip"),
            sorted(x for x, _ in n.get_service_names_and_types_by_node("counter", "/own") if "flip" in x),
            m.get_client_names_and_types_by_node("other", "/own"), c.service_is_ready()])
out.append(["nodes", sorted(f for f in n.get_fully_qualified_node_names() if f.startswith("/own"))])
out.append(["infos", [[i.node_name, i.node_namespace, i.topic_type]
                      for i in n.get_subscriptions_info_by_topic("/own/chatter")]])
m.destroy_subscription(s)
out.append(["after destroy", n.count_subscribers("chatter"),
            m.get_subscriber_names_and_types_by_node("other", "/own")])
m.destroy_node()
out.append(["after node gone", sorted(f for f in n.get_fully_qualified_node_names() if f.startswith("/own"))])
n.destroy_node()
rclpy.shutdown()
print(json.dumps(out))
