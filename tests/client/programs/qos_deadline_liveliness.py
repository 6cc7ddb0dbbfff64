# The QoS events of ros2/demos' quality_of_service_demo_py (deadline, liveliness, lifespan) as a user observes
# them: which events come, with which counts, in which phases. Periods are generous and counts are checked
# against the time that really passed, so a loaded machine changes no observation.
import itertools
import json
import time

import rclpy
from rclpy.duration import Duration
from rclpy.event_handler import (
    PublisherEventCallbacks,
    QoSLivelinessChangedInfo,
    QoSLivelinessLostInfo,
    QoSOfferedDeadlineMissedInfo,
    QoSPublisherEventType,
    QoSRequestedDeadlineMissedInfo,
    QoSSubscriptionEventType,
    SubscriptionEventCallbacks,
)
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, LivelinessPolicy, QoSProfile
from std_msgs.msg import String

out = []
events = []


def on(kind):
    def record(event):
        fields = ("alive_count", "not_alive_count", "alive_count_change", "not_alive_count_change") \
            if kind == "changed" else ("total_count", "total_count_change")
        events.append([kind, type(event).__name__, *[getattr(event, f) for f in fields]])
    return record


def take_events():
    taken = list(events)
    events.clear()
    return taken


rclpy.init()
node = Node("qos_events_demo")
ex = SingleThreadedExecutor()
ex.add_node(node)


def spin_for(seconds, each=None, every_s=0.0):
    end = time.monotonic() + seconds
    next_s = time.monotonic()
    while time.monotonic() < end:
        if each is not None and time.monotonic() >= next_s:
            each()
            next_s += every_s
        ex.spin_once(timeout_sec=0.02)


out.append(["event types", [[name, int(e)] for name, e in QoSPublisherEventType.__members__.items()],
            [[name, int(e)] for name, e in QoSSubscriptionEventType.__members__.items()]])
out.append(["infos", [sorted(k for k in dir(c()) if not k.startswith("_")) for c in (
    QoSOfferedDeadlineMissedInfo, QoSRequestedDeadlineMissedInfo, QoSLivelinessLostInfo, QoSLivelinessChangedInfo)]])

# Deadline (the deadline demo): a talker and a listener with a 0.3 s deadline; the talker pauses.
PERIOD_S = 0.3
deadline = QoSProfile(depth=10, deadline=Duration(seconds=PERIOD_S))
sub = node.create_subscription(String, "deadline_chatter", lambda m: None, deadline,
                               event_callbacks=SubscriptionEventCallbacks(deadline=on("requested")))
pub = node.create_publisher(String, "deadline_chatter", deadline,
                            event_callbacks=PublisherEventCallbacks(deadline=on("offered")))
out.append(["handlers", [type(h).__name__ for h in pub.event_handlers],
            [h.event_type.name for h in sub.event_handlers]])
spin_for(0.8)
out.append(["deadline: nothing published yet", take_events()])
spin_for(0.8, lambda: pub.publish(String(data="x")), 0.05)
out.append(["deadline: publishing every 50 ms", take_events()])
pub.publish(String(data="last"))
last_s = time.monotonic()
spin_for(1.0)
gap_s = time.monotonic() - last_s
paused = take_events()
for kind in ("offered", "requested"):
    totals = [0, *[e[2] for e in paused if e[0] == kind]]
    changes = [e[3] for e in paused if e[0] == kind]
    expected = int(gap_s / PERIOD_S)  # whole periods without a sample; the last may not have been run yet
    out.append([f"deadline: {kind} while paused", [b - a for a, b in itertools.pairwise(totals)] == changes,
                expected - 1 <= totals[-1] <= expected])
spin_for(0.8, lambda: pub.publish(String(data="again")), 0.05)
out.append(["deadline: publishing again", take_events()])
node.destroy_publisher(pub)
spin_for(0.8)
after = take_events()
out.append(["deadline: publisher gone", sorted(set(e[0] for e in after)), len(after) >= 1])
node.destroy_subscription(sub)

# Liveliness, MANUAL_BY_TOPIC (the liveliness demo with --policy MANUAL_BY_TOPIC): a 1 s lease asserted by
# publishing or by assert_liveliness(), then lost.
LEASE_S = 1.0
manual = QoSProfile(depth=10, liveliness=LivelinessPolicy.MANUAL_BY_TOPIC,
                    liveliness_lease_duration=Duration(seconds=LEASE_S))
sub = node.create_subscription(String, "manual_chatter", lambda m: None, manual,
                               event_callbacks=SubscriptionEventCallbacks(liveliness=on("changed")))
pub = node.create_publisher(String, "manual_chatter", manual,
                            event_callbacks=PublisherEventCallbacks(liveliness=on("lost")))
spin_for(1.3)
out.append(["manual: never asserted", take_events()])
pub.publish(String(data="alive"))
spin_for(0.3)
out.append(["manual: published once", take_events()])
spin_for(LEASE_S + 0.4)
out.append(["manual: lease ran out", sorted(take_events())])
pub.assert_liveliness()
spin_for(0.3)
out.append(["manual: asserted", take_events()])
spin_for(1.6, pub.assert_liveliness, 0.2)
out.append(["manual: asserted every 0.2 s", take_events()])
spin_for(LEASE_S + 0.4)
out.append(["manual: stopped asserting", sorted(take_events())])
node.destroy_publisher(pub)
spin_for(0.4)
out.append(["manual: not-alive publisher gone", take_events()])
node.destroy_subscription(sub)

# Liveliness, AUTOMATIC with a finite lease (the liveliness demo's default): alive from the first message,
# gone when the talker's node is destroyed.
automatic = QoSProfile(depth=10, liveliness=LivelinessPolicy.AUTOMATIC, liveliness_lease_duration=Duration(seconds=1.0))
sub = node.create_subscription(String, "auto_chatter", lambda m: None, automatic,
                               event_callbacks=SubscriptionEventCallbacks(liveliness=on("changed")))
talker = Node("talker")
ex.add_node(talker)
pub = talker.create_publisher(String, "auto_chatter", automatic,
                              event_callbacks=PublisherEventCallbacks(liveliness=on("lost")))
spin_for(1.5, lambda: pub.publish(String(data="hi")), 0.1)
out.append(["automatic: publishing", take_events()])
ex.remove_node(talker)
talker.destroy_node()
spin_for(0.5)
out.append(["automatic: talker destroyed", take_events()])
spin_for(0.5)
out.append(["automatic: nothing more", take_events()])
node.destroy_subscription(sub)

# Lifespan (the lifespan demo): a transient-local talker with a 1 s lifespan; a listener joining later gets
# only the samples still young enough; a sample older than the lifespan leaves the listener's queue untaken.
lifespan = QoSProfile(depth=10, durability=DurabilityPolicy.TRANSIENT_LOCAL, lifespan=Duration(seconds=1.0))
pub = node.create_publisher(String, "lifespan_chatter", lifespan)
for i in range(6):
    pub.publish(String(data=str(i)))
    time.sleep(0.2)
time.sleep(0.3)
heard = []
node.create_subscription(String, "lifespan_chatter", lambda m: heard.append(m.data), lifespan)
spin_for(1.0)
numbers = [str(i) for i in range(6)]
out.append(["lifespan: late joiner", bool(heard) and heard == numbers[-len(heard):], "0" not in heard, "5" in heard])
heard.clear()
for i in range(3):
    pub.publish(String(data=f"queued {i}"))
time.sleep(1.3)
spin_for(0.3)
out.append(["lifespan: expired in the queue", heard])
pub.publish(String(data="fresh"))
spin_for(0.3)
out.append(["lifespan: fresh", heard])
print(json.dumps(out))
