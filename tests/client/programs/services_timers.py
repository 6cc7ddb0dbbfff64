# Services, clients and timers as a user observes them.
import json
import threading
import time

import rclpy
from rclpy.executors import MultiThreadedExecutor, SingleThreadedExecutor
from rclpy.node import Node
from std_srvs.srv import SetBool, Trigger

out = []
rclpy.init()
server = Node("server_demo")
client_node = Node("client_demo")


def handle(req, resp):
    resp.success = not req.data
    resp.message = f"flipped {req.data}"
    return resp


server.create_service(SetBool, "flip", handle)
server.create_service(Trigger, "broken", lambda req, resp: None)
cli = client_node.create_client(SetBool, "flip")
missing = client_node.create_client(SetBool, "nobody_serves_this")
out.append(["wait_for_service", cli.wait_for_service(timeout_sec=5.0)])
t0 = time.monotonic()
out.append(["wait missing", [missing.wait_for_service(timeout_sec=0.5), missing.service_is_ready()]])
out.append(["wait missing took", round(time.monotonic() - t0, 1) >= 0.5])
ex = SingleThreadedExecutor()
ex.add_node(server)
ex.add_node(client_node)
future = cli.call_async(SetBool.Request(data=True))
ex.spin_until_future_complete(future, timeout_sec=5)
r = future.result()
out.append(["call_async", [future.done(), r.success, r.message, type(r).__name__]])
try:
    cli.call_async(Trigger.Request())
    out.append(["wrong request type", "accepted"])
except TypeError as e:
    out.append(["wrong request type", "TypeError " + str(e)])
bad = client_node.create_client(Trigger, "broken")
bad.wait_for_service(timeout_sec=5)
bad_future = bad.call_async(Trigger.Request())
try:
    ex.spin_until_future_complete(bad_future, timeout_sec=2)
    out.append(["handler returned None", "no error"])
except TypeError as e:
    out.append(["handler returned None", "TypeError " + str(e)])
out.append(["broken future done", bad_future.done()])

# A blocking call() from another thread while a MultiThreadedExecutor spins.
mt = MultiThreadedExecutor(num_threads=2)
mt.add_node(server)
mt.add_node(client_node)
spinner = threading.Thread(target=mt.spin, daemon=True)
spinner.start()
resp = cli.call(SetBool.Request(data=False), timeout_sec=5)
out.append(["call from thread", [resp.success, resp.message]])
out.append(["call timeout", missing.call(SetBool.Request(data=False), timeout_sec=0.3)])
mt.shutdown()
spinner.join(2)

# Timers.
node = Node("timer_demo")
count = {"n": 0, "late": 0}
start = time.monotonic()
t = node.create_timer(0.1, lambda: count.__setitem__("n", count["n"] + 1))
late = node.create_timer(0.05, lambda: count.__setitem__("late", count["late"] + 1), autostart=False)
out.append(["period ns", t.timer_period_ns])
out.append(["autostart false", [late.is_canceled(), late.time_until_next_call()]])
ex2 = SingleThreadedExecutor()
ex2.add_node(node)
# Waits on the calls, not on a wall-clock span (a loaded machine runs fewer in one): the third call of a 10 Hz
# timer comes 0.3 s after its creation at the earliest.
while count["n"] < 3 and time.monotonic() < start + 10:
    ex2.spin_once(timeout_sec=0.05)
out.append(["3 calls at 10 Hz take >= 0.25 s", [count["n"] >= 3, time.monotonic() - start >= 0.25]])
out.append(["not started", count["late"]])
t.cancel()
out.append(["cancelled", [t.is_canceled(), t.time_until_next_call(), t.is_ready()]])
late.reset()
n_before = count["n"]
end = time.monotonic() + 10
while count["late"] < 2 and time.monotonic() < end:
    ex2.spin_once(timeout_sec=0.05)
out.append(["after reset", [count["late"] >= 2, count["n"] == n_before]])
out.append(["destroy timer", [node.destroy_timer(late), node.destroy_timer(late)]])
for n in (server, client_node, node):
    n.destroy_node()
rclpy.shutdown()
print(json.dumps(out))
