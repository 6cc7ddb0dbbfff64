# A node's parameter services are run by the executor: nothing is answered before the node spins (a subclass
# declares its parameters after super().__init__()), and the set callbacks run on the spinning thread.
import json
import threading
import time

import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.parameter_client import AsyncParameterClient

out = []
rclpy.init()
target = Node("late_declarer")
user = Node("param_caller")
client = AsyncParameterClient(user, "late_declarer")
out.append(["wait_for_services", client.wait_for_services(timeout_sec=10.0)])
future = client.set_parameters([Parameter("demo_parameter_1", value=True)])
user_ex = SingleThreadedExecutor()
user_ex.add_node(user)
deadline = time.monotonic() + 1.0
while time.monotonic() < deadline and not future.done():
    user_ex.spin_once(timeout_sec=0.05)
out.append(["answered before the target spins", future.done()])
threads = []


def on_set(params):
    threads.append(threading.current_thread() is threading.main_thread())
    from rcl_interfaces.msg import SetParametersResult

    return SetParametersResult(successful=True)


target.declare_parameter("demo_parameter_1", False)
target.add_on_set_parameters_callback(on_set)
ex = SingleThreadedExecutor()
ex.add_node(target)
ex.add_node(user)
ex.spin_until_future_complete(future, timeout_sec=10)
out.append(["set", [[r.successful, r.reason] for r in future.result().results]])
out.append(["value", target.get_parameter("demo_parameter_1").value])
out.append(["callback on the spinning thread", threads])
out.append(["services of the node", sorted(s.srv_name for s in target.services)])
rclpy.shutdown()
print(json.dumps(out))
