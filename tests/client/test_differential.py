"""The same small programs under the real rclpy (Jazzy wheels, Fast DDS on loopback) and under diffctl's
client library must agree on everything a user observes: parameter API results and exceptions, executor
and callback-group ordering, coroutine callbacks and futures, timers, services and clients, QoS (the
transient-local late joiner, incompatible QoS reported in rclpy's words)."""

from __future__ import annotations

from tests.client.differential import assert_same, run_both


def test_parameters_agree(router: str) -> None:
    assert_same(*run_both("params_api.py", router))


def test_executors_and_callback_groups_agree(router: str) -> None:
    assert_same(*run_both("executors_order.py", router))


def test_services_and_timers_agree(router: str) -> None:
    assert_same(*run_both("services_timers.py", router))


def test_qos_agrees(router: str) -> None:
    oracle, ours = run_both("qos_events.py", router)
    assert_same(oracle, ours)
    warnings = sorted(set(line for line in oracle.log_lines() if line.startswith("[WARN]")))
    assert warnings, oracle.stderr
    assert sorted(set(line for line in ours.log_lines() if line.startswith("[WARN]"))) == warnings


def test_topics_graph_logging_agree(router: str) -> None:
    assert_same(*run_both("topics_misc.py", router))


def test_sim_time_agrees(router: str) -> None:
    assert_same(*run_both("sim_time.py", router))


def test_ros_args_agree(router: str) -> None:
    assert_same(*run_both("ros_args.py", router))


def test_parameter_events_and_logger_services_agree(router: str) -> None:
    assert_same(*run_both("param_events.py", router))


def test_parameter_services_agree(router: str) -> None:
    """Another node's parameter services through AsyncParameterClient: the same answers as rclpy's."""
    assert_same(*run_both("param_client.py", router))


def test_logging_switches_agree(router: str) -> None:
    oracle, ours = run_both("logging_switches.py", router)
    assert_same(oracle, ours)
    assert ours.log_lines() == oracle.log_lines()


def test_values_agree(router: str) -> None:
    """QoS profiles as printed, the compatibility check's verdict and words for every policy pairing, time and
    parameter values, logging severities."""
    assert_same(*run_both("values.py", router))


def test_node_api_details_agree(router: str) -> None:
    assert_same(*run_both("node_api.py", router))


def test_own_endpoints_are_counted_at_once(router: str) -> None:
    assert_same(*run_both("own_endpoints.py", router))


def test_name_validation_agrees(router: str) -> None:
    assert_same(*run_both("names_graph.py", router))


def test_qos_deadline_liveliness_lifespan_agree(router: str) -> None:
    """ros2/demos' deadline, liveliness and lifespan demos' situations: the same events with the same counts
    (rmw_zenoh has none of them; diffctl's client counts them as Fast DDS does)."""
    assert_same(*run_both("qos_deadline_liveliness.py", router))


_RMW_ZENOH_QOS = """
import time
import rclpy
from rclpy.duration import Duration
from rclpy.event_handler import PublisherEventCallbacks, SubscriptionEventCallbacks
from rclpy.node import Node
from rclpy.qos import QoSProfile
from std_msgs.msg import String
rclpy.init()
node = Node("rmw_zenoh_qos")
for make in (lambda: node.create_publisher(String, "a", 10, event_callbacks=PublisherEventCallbacks(deadline=print)),
             lambda: node.create_subscription(String, "a", print, 10,
                                              event_callbacks=SubscriptionEventCallbacks(liveliness=print))):
    try:
        make()
        print("created")
    except Exception as e:
        print(type(e).__name__, e)
qos = QoSProfile(depth=10, lifespan=Duration(seconds=0.1))
heard = []
pub = node.create_publisher(String, "b", qos)
node.create_subscription(String, "b", lambda m: heard.append(m.data), qos)
while pub.get_subscription_count() == 0:
    rclpy.spin_once(node, timeout_sec=0.05)
pub.publish(String(data="old"))
time.sleep(0.5)
rclpy.spin_once(node, timeout_sec=2.0)
print(heard)
"""


def test_rmw_zenoh_qos_behaviour_behind_the_switch(router: str) -> None:
    """DIFFCTL_QOS_EVENTS=rmw_zenoh: deadline and liveliness callbacks refused as rclpy on rmw_zenoh refuses them,
    and a lifespan expires nothing."""
    import os
    import subprocess
    import sys

    p = subprocess.run([sys.executable, "-c", _RMW_ZENOH_QOS], capture_output=True, text=True, timeout=60,
                       env={**os.environ, "DIFFCTL_QOS_EVENTS": "rmw_zenoh"})
    assert p.returncode == 0, p.stderr
    refusal = "UnsupportedEventTypeError Failed to create event handler: event type is not supported by rmw_zenoh_cpp"
    assert p.stdout.splitlines() == [refusal, refusal, "['old']"]
