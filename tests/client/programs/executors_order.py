# Executor and callback-group ordering, futures and coroutine callbacks, as a user observes them.
import json
import threading
import time

import rclpy
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
from rclpy.executors import MultiThreadedExecutor, SingleThreadedExecutor
from rclpy.node import Node
from rclpy.task import Future
from rclpy.waitable import NumberOfEntities, Waitable
from std_msgs.msg import String

out = []
rclpy.init()
node = Node("order_demo")
events = []
pub = node.create_publisher(String, "order_topic", 10)
sub = node.create_subscription(String, "order_topic", lambda m: events.append("sub " + m.data), 10)
ex = SingleThreadedExecutor()
ex.add_node(node)
deadline = time.monotonic() + 5
while pub.get_subscription_count() < 1 and time.monotonic() < deadline:
    ex.spin_once(timeout_sec=0.05)
for i in range(3):
    pub.publish(String(data=str(i)))
time.sleep(0.5)  # every sample delivered, the timer due, before anything runs


def on_timer():
    events.append("timer")
    tmr.cancel()


tmr = node.create_timer(0.01, on_timer)
gc = node.create_guard_condition(lambda: events.append("guard"))
gc.trigger()
time.sleep(0.05)
ex.create_task(lambda: events.append("task"))
for _ in range(6):
    ex.spin_once(timeout_sec=0.5)
out.append(["single-threaded order", events[:6]])

# A coroutine callback awaiting a future that another callback completes.
events.clear()
fut = Future()


async def waiter():
    t1.cancel()
    events.append("waiting")
    value = await fut
    events.append(f"resumed with {value}")


t1 = node.create_timer(0.01, waiter, callback_group=ReentrantCallbackGroup())
t2 = node.create_timer(0.05, lambda: (fut.set_result(7), t2.cancel()), callback_group=ReentrantCallbackGroup())
end = time.monotonic() + 2
while time.monotonic() < end and "resumed with 7" not in events:
    ex.spin_once(timeout_sec=0.1)
out.append(["coroutine", events[:2]])

# spin_until_future_complete: a timeout returns quietly; a done future returns at once.
never = Future()
t0 = time.monotonic()
ex.spin_until_future_complete(never, timeout_sec=0.3)
out.append(["timeout returns", [never.done(), never.result(), time.monotonic() - t0 >= 0.25]])  # not early
done = Future()
done.set_result("x")
ex.spin_until_future_complete(done, timeout_sec=1)
out.append(["done future", done.result()])
c = Future()
called = []
c.add_done_callback(lambda f: called.append("done callback"))
c.cancel()
out.append(["cancelled future", [c.cancelled(), c.done(), c.result(), called]])
c.cancel()
c.set_result(1)
out.append(["result after cancel", [c.cancelled(), c.done(), c.result()]])
t0 = time.monotonic()
pending = Future()
threading.Timer(0.2, pending.cancel).start()
ex.spin_until_future_complete(pending, timeout_sec=2)
out.append(["spin ends on cancel", round(time.monotonic() - t0, 1) < 1.0])
cb = Future()
cb_hits = []
hit = cb_hits.append
cb.add_done_callback(hit)
out.append(["remove done callback", [cb.remove_done_callback(hit), cb.remove_done_callback(hit)]])


async def cancellable():
    await Future()


task = ex.create_task(cancellable)
ex.spin_once(timeout_sec=0.1)
task.cancel()
ex.spin_once(timeout_sec=0.1)
out.append(["cancelled task", [task.cancelled(), task.done(), task.executing()]])

# Several tasks: the newest pending task runs first; a done callback of a future that knows its executor
# becomes a task too.
order = []
for name in ("t1", "t2", "t3"):
    ex.create_task(lambda name=name: order.append(name))
f_exec = Future(executor=ex)
f_exec.add_done_callback(lambda f: order.append("done callback"))
f_exec.set_result(1)
for _ in range(4):
    ex.spin_once(timeout_sec=0.1)
out.append(["task order", order])

# A callback that raises: spin_once propagates it.
boom = node.create_timer(0.01, lambda: 1 / 0)
try:
    for _ in range(5):
        ex.spin_once(timeout_sec=0.5)
    out.append(["exception", "none"])
except ZeroDivisionError as e:
    out.append(["exception", type(e).__name__ + ": " + str(e)])
node.destroy_timer(boom)
ex.remove_node(node)


def overlap(group_factory):
    n = Node("overlap_demo")
    state = {"now": 0, "max": 0, "calls": 0}
    lock = threading.Lock()

    def slow():
        with lock:
            state["now"] += 1
            state["calls"] += 1
            state["max"] = max(state["max"], state["now"])
        time.sleep(0.15)
        with lock:
            state["now"] -= 1

    group = group_factory()
    timers = [n.create_timer(0.05, slow, callback_group=group) for _ in range(2)]
    mt = MultiThreadedExecutor(num_threads=4)
    mt.add_node(n)
    end = time.monotonic() + 1.0
    while time.monotonic() < end:
        mt.spin_once(timeout_sec=0.05)
    for t in timers:
        t.cancel()
    mt.shutdown()
    n.destroy_node()
    return state["max"]


class Watcher(Waitable):
    """A user's waitable that never has work: it only records that an executor asked it into a wait."""

    def __init__(self):
        super().__init__(ReentrantCallbackGroup())
        self.asked = threading.Event()

    def add_to_wait_set(self, wait_set):
        self.asked.set()

    def get_num_entities(self):
        return NumberOfEntities()

    def is_ready(self, wait_set):
        return False

    def take_data(self):
        raise AssertionError("a waitable that is never ready is never taken from")

    async def execute(self, taken_data):
        raise AssertionError("a waitable that is never ready never runs")


watched = Node("waitable_demo")
spinning = SingleThreadedExecutor()
spinning.add_node(watched)
spinner = threading.Thread(target=spinning.spin, daemon=True)
spinner.start()
time.sleep(0.2)  # let the executor settle into its wait, so the waitable arrives while it waits
watcher = Watcher()
watched.add_waitable(watcher)
out.append(["a waitable added while spinning joins the wait", watcher.asked.wait(5.0)])
watched.remove_waitable(watcher)
spinning.shutdown()
spinner.join(5.0)
watched.destroy_node()

out.append(["mutually exclusive max overlap", overlap(MutuallyExclusiveCallbackGroup)])
out.append(["reentrant callbacks overlap", overlap(ReentrantCallbackGroup) >= 2])
out.append(["default group is exclusive", isinstance(node.default_callback_group, MutuallyExclusiveCallbackGroup)])
node.destroy_node()
rclpy.shutdown()
print(json.dumps(out))
