# A node whose context was shut down (a callback still running at Ctrl-C, code after rclpy.shutdown()):
# rclpy's RCLError for what needs the context, what still works.
import json

import rclpy
from rclpy.context import Context
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from std_msgs.msg import String
from std_srvs.srv import SetBool

out = []


def obs(label, fn):
    try:
        result = fn()
        plain = isinstance(result, (bool, int, str, type(None), list))
        out.append([label, "ok", result if plain else type(result).__name__])
    except Exception as e:
        out.append([label, type(e).__name__, str(e)])


obs("executor before init", lambda: SingleThreadedExecutor())
rclpy.init()
node = Node("late_publisher")
pub = node.create_publisher(String, "late", 10)
sub = node.create_subscription(String, "late", lambda m: None, 10)
cli = node.create_client(SetBool, "svc")
srv = node.create_service(SetBool, "svc", lambda a, b: b)
timer = node.create_timer(1.0, lambda: None)
guard = node.create_guard_condition(lambda: None)
pub.publish(String(data="before"))
rclpy.shutdown()
obs("publish after shutdown", lambda: pub.publish(String(data="after")))
obs("publish bytes", lambda: pub.publish(b"\x00\x01\x00\x00\x01\x00\x00\x00\x00"))
obs("publisher", lambda: node.create_publisher(String, "t2", 10))
obs("publisher with a bad name", lambda: node.create_publisher(String, "a//b", 10))
obs("subscription", lambda: node.create_subscription(String, "t2", lambda m: None, 10))
obs("client", lambda: node.create_client(SetBool, "s2"))
obs("client with a bad name", lambda: node.create_client(SetBool, "a//b"))
obs("service", lambda: node.create_service(SetBool, "s2", lambda a, b: b))
obs("timer", lambda: node.create_timer(1.0, lambda: None))
obs("rate", lambda: node.create_rate(1.0))
obs("guard condition", lambda: node.create_guard_condition(lambda: None))
for query in ("count_publishers", "count_subscribers", "count_clients", "count_services",
              "get_publishers_info_by_topic", "get_subscriptions_info_by_topic"):
    obs(query, lambda query=query: getattr(node, query)("late"))
for query in ("get_topic_names_and_types", "get_service_names_and_types", "get_node_names",
              "get_node_names_and_namespaces", "get_node_names_and_namespaces_with_enclaves",
              "get_fully_qualified_node_names"):
    obs(query, lambda query=query: getattr(node, query)())
for query in ("get_publisher_names_and_types_by_node", "get_subscriber_names_and_types_by_node",
              "get_service_names_and_types_by_node", "get_client_names_and_types_by_node"):
    obs(query, lambda query=query: getattr(node, query)("late_publisher", "/"))
obs("wait_for_node", lambda: node.wait_for_node("/late_publisher", 0.1))
obs("get_subscription_count", lambda: pub.get_subscription_count())
obs("get_publisher_count", lambda: sub.get_publisher_count())
obs("assert_liveliness", lambda: pub.assert_liveliness())
obs("wait_for_all_acked", lambda: pub.wait_for_all_acked())
obs("service_is_ready", lambda: cli.service_is_ready())
obs("wait_for_service", lambda: cli.wait_for_service(timeout_sec=0.1))
obs("resolve", lambda: node.resolve_topic_name("x"))
obs("get_parameter", lambda: node.get_parameter("use_sim_time").value)
obs("clock", lambda: node.get_clock().now().nanoseconds > 0)
obs("log", lambda: node.get_logger().info("after shutdown"))
obs("timer cancel", lambda: timer.cancel())
obs("guard trigger", lambda: guard.trigger())
obs("executor", lambda: SingleThreadedExecutor())
obs("spin_once", lambda: rclpy.spin_once(node, timeout_sec=0))
obs("ok", lambda: rclpy.ok())
obs("destroy", lambda: [node.destroy_subscription(sub), node.destroy_client(cli), node.destroy_service(srv),
                        node.destroy_timer(timer), node.destroy_guard_condition(guard), node.destroy_publisher(pub)])
obs("destroy node", lambda: node.destroy_node())
obs("node", lambda: Node("again"))


def as_printed(fn):
    """The last traceback line a user sees (the binding's exceptions name rclpy._rclpy_pybind11) and the classes
    an `except` can catch them by."""
    import traceback
    try:
        fn()
        return "no error"
    except Exception as e:
        return [traceback.format_exception_only(e)[-1].strip(),
                [c.__name__ for c in type(e).__mro__ if c.__module__.split(".")[0] in ("builtins", "rclpy")]]


def destroyed_handle():
    with pub.handle:
        pass


out.append(["printed: publish after shutdown", as_printed(lambda: pub.publish(String(data="x")))])
out.append(["printed: a second shutdown", as_printed(rclpy.shutdown)])
out.append(["printed: a destroyed publisher's handle", as_printed(destroyed_handle)])
out.append(["printed: a malformed remap rule, its class", as_printed(
    lambda: rclpy.init(args=["--ros-args", "-r", "a"], context=Context()))[0].split(":")[0]])
out.append(["printed: not a ROS flag", as_printed(lambda: rclpy.init(args=["--ros-args", "--no-such-flag"],
                                                                   context=Context()))])
print(json.dumps(out))
