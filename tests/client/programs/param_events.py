# Parameter events (ParameterEventHandler, as the "monitoring parameter changes" tutorial uses it), how
# many events a declare_parameters and an atomic set make, and the logger-level services of a node created
# with enable_logger_service=True.
import json
import time

import rclpy
from rcl_interfaces.msg import LoggerLevel
from rcl_interfaces.srv import GetLoggerLevels, SetLoggerLevels
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.parameter_event_handler import ParameterEventHandler

out = []
rclpy.init()
watched = Node("watched", namespace="ns", enable_logger_service=True)
watcher = Node("watcher", namespace="ns")
ex = SingleThreadedExecutor()
ex.add_node(watched)
ex.add_node(watcher)


def spin_until(cond, seconds=5.0):
    end = time.monotonic() + seconds
    while time.monotonic() < end and not cond():
        ex.spin_once(timeout_sec=0.05)


seen, events = [], []
handler = ParameterEventHandler(watcher)
h1 = handler.add_parameter_callback("gain", "watched", lambda p: seen.append(["first", p.name, p.value.double_value]))
handler.add_parameter_callback("gain", "/ns/watched", lambda p: seen.append(["second", p.name,
                                                                              p.value.double_value]))
eh = handler.add_parameter_event_callback(lambda e: events.append(
    [e.node, [p.name for p in ParameterEventHandler.get_parameters_from_event(e)],
     [p.name for p in e.deleted_parameters]]))
spin_until(lambda: watcher.count_publishers("/parameter_events") >= 2, 5)
spin_until(lambda: False, 0.5)
watched.declare_parameter("gain", 1.0)
spin_until(lambda: len(seen) >= 2)
watched.set_parameters([Parameter("gain", value=2.5)])
spin_until(lambda: len(seen) >= 4)
handler.remove_parameter_callback(h1)
watched.set_parameters([Parameter("gain", value=3.0)])
spin_until(lambda: len(seen) >= 5)
spin_until(lambda: False, 0.3)
out.append(["parameter callbacks", seen])
out.append(["events of watched", [e for e in events if e[0] == "/ns/watched"]])
# declare_parameters: one event per parameter (rclpy sets them one by one); an atomic set: one event for all
events.clear()
watched.declare_parameters("", [("a", 1), ("b", "x"), ("c", [1.0])])
watched.set_parameters_atomically([Parameter("a", value=2), Parameter("b", value="y")])
spin_until(lambda: len([e for e in events if e[0] == "/ns/watched"]) >= 4)
spin_until(lambda: False, 0.3)
out.append(["events of declare_parameters and an atomic set", [e for e in events if e[0] == "/ns/watched"]])
try:
    handler.remove_parameter_callback(h1)
except RuntimeError as e:
    out.append(["remove twice", str(e)])
handler.remove_parameter_event_callback(eh)
# the handler's registry (rclpy's handler._callbacks), which a subclass feeds events through
out.append(["registry", [sorted(handler._callbacks.parameter_callbacks), len(handler._callbacks.event_callbacks)]])

services = sorted(s for s, _ in watcher.get_service_names_and_types() if "logger_levels" in s)
out.append(["logger services", services])
get = watcher.create_client(GetLoggerLevels, "/ns/watched/get_logger_levels")
put = watcher.create_client(SetLoggerLevels, "/ns/watched/set_logger_levels")
get.wait_for_service(timeout_sec=5)
put.wait_for_service(timeout_sec=5)
f = put.call_async(SetLoggerLevels.Request(levels=[LoggerLevel(name="ns.watched", level=10),
                                                   LoggerLevel(name="ns.watched", level=15)]))
ex.spin_until_future_complete(f, timeout_sec=5)
out.append(["set levels", [[r.successful, r.reason] for r in f.result().results]])
f = get.call_async(GetLoggerLevels.Request(names=["ns.watched", "unknown.logger"]))
ex.spin_until_future_complete(f, timeout_sec=5)
out.append(["get levels", [[lv.name, lv.level] for lv in f.result().levels]])
out.append(["debug enabled now", watched.get_logger().is_enabled_for(10)])
handler.destroy()
watched.destroy_node()
watcher.destroy_node()
rclpy.shutdown()
print(json.dumps(out))
