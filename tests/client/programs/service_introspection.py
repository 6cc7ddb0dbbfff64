# Service introspection as the introspection demo uses it: configure_introspection on a service and a client
# publishes <service>/_service_event (request sent/received, response sent/received), with the contents or
# the metadata only, and nothing once OFF. (The client GID is left out: Fast DDS gives the service side its
# request writer's GUID, rmw_zenoh the client's own GID on both sides.)
import json
import time

import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import qos_profile_system_default
from rclpy.service_introspection import ServiceIntrospectionState
from std_srvs.srv import SetBool

out = [["states", [[n, int(getattr(ServiceIntrospectionState, n))] for n in ("OFF", "METADATA", "CONTENTS")]]]
rclpy.init()
server = Node("introspection_service")
srv = server.create_service(SetBool, "add_two_ints",
                            lambda req, resp: setattr(resp, "message", f"got {req.data}") or resp)
user = Node("introspection_client")
cli = user.create_client(SetBool, "add_two_ints")
watcher = Node("event_watcher")
events = []
watcher.create_subscription(SetBool.Event, "add_two_ints/_service_event", events.append, 10)
ex = SingleThreadedExecutor()
for n in (server, user, watcher):
    ex.add_node(n)
out.append(["service ready", cli.wait_for_service(timeout_sec=10.0)])


def settle(seconds):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        ex.spin_once(timeout_sec=0.05)


def call_and_collect(expected):
    events.clear()
    future = cli.call_async(SetBool.Request(data=True))
    ex.spin_until_future_complete(future, timeout_sec=10)
    end = time.monotonic() + 5
    while time.monotonic() < end and len(events) < expected:
        ex.spin_once(timeout_sec=0.05)
    settle(0.3)
    seen = sorted([e.info.event_type, [r.data for r in e.request],
            [r.message for r in e.response]] for e in events)
    seqs = {e.info.sequence_number for e in events}
    return [future.result().message, seen, len(seqs), all(e.info.stamp.sec > 0 for e in events)]


for state in (ServiceIntrospectionState.CONTENTS, ServiceIntrospectionState.METADATA):
    srv.configure_introspection(server.get_clock(), qos_profile_system_default, state)
    cli.configure_introspection(user.get_clock(), qos_profile_system_default, state)
    settle(1.0)  # the watcher discovers the new publishers
    out.append([state.name, call_and_collect(4)])
srv.configure_introspection(server.get_clock(), qos_profile_system_default, ServiceIntrospectionState.OFF)
cli.configure_introspection(user.get_clock(), qos_profile_system_default, ServiceIntrospectionState.OFF)
out.append(["OFF", call_and_collect(0)])
rclpy.shutdown()
print(json.dumps(out))
