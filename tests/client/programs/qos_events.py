# QoS as a user observes it: a transient-local late joiner gets the newest samples, a volatile one none;
# incompatible QoS is reported (default warnings and a user callback).
import json
import re
import time

import rclpy
from rclpy.event_handler import SubscriptionEventCallbacks
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy, qos_policy_name_from_kind
from std_msgs.msg import String

out = []
rclpy.init()
node = Node("qos_demo")
ex = SingleThreadedExecutor()
ex.add_node(node)


def spin_for(seconds):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        ex.spin_once(timeout_sec=0.05)


latched = QoSProfile(depth=2, durability=DurabilityPolicy.TRANSIENT_LOCAL)
pub = node.create_publisher(String, "latched_topic", latched)
for word in ("a", "b", "c"):
    pub.publish(String(data=word))
spin_for(0.5)
late, volatile = [], []
node.create_subscription(String, "latched_topic", lambda m: late.append(m.data),
                         QoSProfile(depth=5, durability=DurabilityPolicy.TRANSIENT_LOCAL))
node.create_subscription(String, "latched_topic", lambda m: volatile.append(m.data), 5)
spin_for(1.5)
out.append(["transient local late joiner", late])
out.append(["volatile late joiner", volatile])

# History: a depth-3 subscription that was not spun keeps the newest three; KEEP_ALL keeps every sample.
from rclpy.qos import HistoryPolicy  # noqa: E402

kept3, kept_all = [], []
burst = node.create_publisher(String, "burst", 20)
node.create_subscription(String, "burst", lambda m: kept3.append(m.data), 3)
node.create_subscription(String, "burst", lambda m: kept_all.append(m.data), QoSProfile(history=HistoryPolicy.KEEP_ALL))
spin_for(1.0)
for i in range(10):
    burst.publish(String(data=str(i)))
time.sleep(1.0)
spin_for(0.5)
out.append(["keep last 3", kept3])
out.append(["keep all", kept_all])

events = []
node.create_publisher(String, "incompatible_topic", QoSProfile(depth=5, reliability=ReliabilityPolicy.BEST_EFFORT))
node.create_subscription(
    String, "incompatible_topic", lambda m: None, QoSProfile(depth=5, reliability=ReliabilityPolicy.RELIABLE),
    event_callbacks=SubscriptionEventCallbacks(
        incompatible_qos=lambda e: events.append(qos_policy_name_from_kind(e.last_policy_kind))))
node.create_subscription(String, "incompatible_topic", lambda m: None,
                         QoSProfile(depth=5, reliability=ReliabilityPolicy.RELIABLE))
# A shorter lease on the subscription (the QoS demo's liveliness_lease_duration case): DDS refuses it under
# LIVELINESS; the kind prints as rclpy's enum (str and f-string: what the demos log).
from rclpy.duration import Duration  # noqa: E402
from rclpy.event_handler import PublisherEventCallbacks  # noqa: E402

offered = []


def on_offered(e):
    # What a callback sees: the kind as printed, the event as printed, and the read-only fields' errors (the
    # liveliness demo reads alive_count off a lost-liveliness status).
    errors = []
    for attempt in (lambda: e.alive_count, lambda: setattr(e, "total_count", 9), lambda: setattr(e, "extra", 1)):
        try:
            attempt()
        except AttributeError as x:
            errors.append(str(x))
    offered.append((qos_policy_name_from_kind(e.last_policy_kind), str(e.last_policy_kind), f"{e.last_policy_kind}",
                    repr(type(e.last_policy_kind)), repr(type(e)),
                    e.total_count, re.sub("0x[0-9a-f]+", "0x", f"{e}"), tuple(errors)))


node.create_publisher(String, "lease_topic", QoSProfile(depth=5, liveliness_lease_duration=Duration(seconds=3)),
                      event_callbacks=PublisherEventCallbacks(incompatible_qos=on_offered))
node.create_subscription(String, "lease_topic", lambda m: None,
                         QoSProfile(depth=5, liveliness_lease_duration=Duration(seconds=1)))
spin_for(1.5)
out.append(["user incompatible qos callback", sorted(set(events))])
out.append(["lease incompatible, kind as printed", sorted(set(offered))])

from rcl_interfaces.msg import SetParametersResult  # noqa: E402
from rclpy.parameter import Parameter  # noqa: E402
from rclpy.qos_overriding_options import InvalidQosOverridesError, QoSOverridingOptions  # noqa: E402

tuned = Node("qos_override_demo", parameter_overrides=[
    Parameter("qos_overrides./tuned.publisher.depth", value=3),
    Parameter("qos_overrides./tuned.publisher.reliability", value="best_effort")])
tuned_pub = tuned.create_publisher(String, "tuned", 10,
                                   qos_overriding_options=QoSOverridingOptions.with_default_policies())
out.append(["qos overrides applied", [tuned_pub.qos_profile.depth, tuned_pub.qos_profile.reliability.name,
                                      tuned_pub.qos_profile.history.name]])
out.append(["qos override parameters", sorted(tuned.get_parameters_by_prefix("qos_overrides"))])
out.append(["qos override read only", tuned.set_parameters(
    [Parameter("qos_overrides./tuned.publisher.depth", value=4)])[0].reason])
try:
    tuned.create_subscription(String, "tuned", lambda m: None, 10, qos_overriding_options=QoSOverridingOptions(
        [], callback=lambda q: SetParametersResult(successful=False, reason="no thanks"), entity_id="mine"))
    out.append(["qos override callback", "accepted"])
except InvalidQosOverridesError as e:
    out.append(["qos override callback", str(e)])

try:  # an override no policy has (ros2/demos' qos_overrides_talker with a bad -p): the traceback as rclpy's
    Node("qos_bad_override", parameter_overrides=[
        Parameter("qos_overrides./bad.publisher.reliability", value="sometimes")]).create_publisher(
        String, "bad", 10, qos_overriding_options=QoSOverridingOptions.with_default_policies())
    out.append(["bad qos override", "accepted"])
except RuntimeError as e:
    out.append(["bad qos override", str(e), repr(e.__context__), e.__suppress_context__])

matched_pub, matched_sub = [], []
mpub = tuned.create_publisher(String, "matched_topic", 10, event_callbacks=PublisherEventCallbacks(
    matched=lambda e: matched_pub.append([e.total_count, e.current_count])))
ex.add_node(tuned)
spin_for(0.5)
msub = node.create_subscription(String, "matched_topic", lambda m: None, 10, event_callbacks=SubscriptionEventCallbacks(
    matched=lambda e: matched_sub.append([e.total_count, e.current_count])))
spin_for(1.0)
node.destroy_subscription(msub)
spin_for(1.0)
out.append(["publisher matched events", matched_pub])
out.append(["subscription matched events", matched_sub])
tuned.destroy_node()
node.destroy_node()
rclpy.shutdown()
print(json.dumps(out))
