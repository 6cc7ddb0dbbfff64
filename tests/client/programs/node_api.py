# Node API details as a user observes them: names, graph queries about a node, errors of destroyed entities,
# descriptions of the built-in parameters, timer and rate argument checks.
import json
import threading
import time

import rclpy
from rclpy.context import Context
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.topic_endpoint_info import TopicEndpointInfo
from std_msgs.msg import String
from std_srvs.srv import SetBool

out = []


def obs(label, fn):
    try:
        out.append([label, "ok", fn()])
    except Exception as e:
        out.append([label, type(e).__name__, str(e)])


def enter(handle):
    """What a `with` block on an entity's handle does: enters, or the error that refuses it."""
    try:
        with handle:
            return "entered"
    except Exception as e:
        return [type(e).__name__, str(e)]


rclpy.init()
n = Node("ex2", namespace="a/b")
obs("ns", lambda: [n.get_namespace(), n.get_fully_qualified_name(), n.get_logger().name])
obs("a new node's publishers", lambda: [x.topic_name for x in n.publishers])
obs("node handle is read-only", lambda: setattr(n, "handle", None))
obs("context handle before init", lambda: Context().handle)
obs("empty endpoint info", lambda: str(TopicEndpointInfo()).splitlines())
p = n.create_publisher(String, "~/private", 10)
obs(
    "topic",
    lambda: [
        p.topic_name,
        n.create_publisher(String, "rel", 10).topic_name,
        n.create_subscription(String, "{node}/x", lambda m: None, 10).topic_name,
    ],
)
obs("bad service", lambda: n.create_client(SetBool, "bad name"))
obs("bad sub topic", lambda: n.create_subscription(String, "1abc", lambda m: None, 10))
s = n.create_service(SetBool, "svc", lambda a, b: b)
c = n.create_client(SetBool, "~/svc2")
obs(
    "service names",
    lambda: [s.srv_name, getattr(s, "service_name", None), c.srv_name, getattr(c, "service_name", None)],
)
obs("handles in use", lambda: [enter(x.handle) for x in (p, s, c, n, n.context)])
obs("destroy twice", lambda: [n.destroy_publisher(p), n.destroy_publisher(p)])
obs("get_parameter_or", lambda: (lambda q: [q.name, q.value])(n.get_parameter_or("nope", Parameter("nope", value=3))))
obs(
    "describe use_sim_time",
    lambda: (lambda d: [d.name, d.type, d.read_only, d.description, d.dynamic_typing])(
        n.describe_parameter("use_sim_time")
    ),
)
obs(
    "describe start_type_description_service",
    lambda: (lambda d: [d.name, d.type, d.read_only, d.description])(
        n.describe_parameter("start_type_description_service")
    ),
)
obs(
    "set start_type_description_service",
    lambda: [r.reason for r in n.set_parameters([Parameter("start_type_description_service", value=False)])],
)
obs("set use_sim_time string", lambda: [r.reason for r in n.set_parameters([Parameter("use_sim_time", value="yes")])])
time.sleep(1.0)
obs("own services", lambda: sorted(x for x, _ in n.get_service_names_and_types_by_node("ex2", "/a/b")))
obs("own publishers", lambda: sorted(x for x, _ in n.get_publisher_names_and_types_by_node("ex2", "/a/b")))
obs("own subscribers", lambda: sorted(x for x, _ in n.get_subscriber_names_and_types_by_node("ex2", "/a/b")))
obs("own clients", lambda: sorted(x for x, _ in n.get_client_names_and_types_by_node("ex2", "/a/b")))
obs("unknown node", lambda: n.get_publisher_names_and_types_by_node("ghost", "/"))
obs("counts", lambda: [n.count_services("svc"), n.count_clients("~/svc2"), n.count_services("/nobody")])
obs("fq names", lambda: "/a/b/ex2" in n.get_fully_qualified_node_names())
obs("wait_for_node", lambda: n.wait_for_node("/a/b/ex2", 1.0))
obs(
    "timer period set",
    lambda: (lambda t: (setattr(t, "timer_period_ns", 5), t.timer_period_ns))(n.create_timer(1.0, lambda: None))[1],
)
obs("rate bad", lambda: n.create_rate(0))
obs("timer negative", lambda: n.create_timer(-1, lambda: None))
gone = n.create_timer(1.0, lambda: None)
obs("destroy timer", lambda: [n.destroy_timer(gone), n.destroy_timer(gone), bool(gone)])
for method in ("cancel", "reset", "is_canceled", "is_ready", "time_since_last_call", "time_until_next_call"):
    obs(f"destroyed timer {method}", getattr(gone, method))
obs("destroyed timer period", lambda: gone.timer_period_ns)
obs("destroyed timer handle", lambda: enter(gone.handle))
obs("publish after destroy", lambda: p.publish(String()))
gc = n.create_guard_condition(lambda: None)
obs("destroy service, client, guard condition", lambda: [n.destroy_service(s), n.destroy_client(c),
                                                         n.destroy_guard_condition(gc)])
obs("handles of destroyed entities", lambda: [enter(x.handle) for x in (p, s, c, gc)])


def rate_keeps_pace():
    """A Rate's sleep after work that overran the period returns at once; two sleepers wake on one tick."""
    executor = SingleThreadedExecutor()
    executor.add_node(n)
    spinner = threading.Thread(target=executor.spin, daemon=True)
    spinner.start()
    rate = n.create_rate(20)
    rate.sleep()
    start = time.monotonic()
    time.sleep(0.07)
    rate.sleep()
    seen = {"overrun": time.monotonic() - start < 0.1}
    woke = []
    sleepers = [threading.Thread(target=lambda: (rate.sleep(), woke.append(time.monotonic()))) for _ in range(2)]
    rate.sleep()
    for s in sleepers:
        s.start()
    for s in sleepers:
        s.join(5)
    seen["two sleepers"] = len(woke) == 2 and abs(woke[0] - woke[1]) < 0.04
    rate.destroy()
    executor.shutdown()
    spinner.join(5)
    return seen


obs("rate keeps pace", rate_keeps_pace)
context_handle = n.context.handle
n.destroy_node()
obs("destroy node twice", lambda: n.destroy_node())
obs("handle of a destroyed node", lambda: enter(n.handle))
rclpy.shutdown()
obs("context handle after shutdown", lambda: enter(context_handle))
print(json.dumps(out, default=lambda o: type(o).__name__))
