# AsyncParameterClient against another node's parameter services (the services served for every node).
import json

import rclpy
from rcl_interfaces.msg import IntegerRange, ParameterDescriptor
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter, parameter_value_to_python
from rclpy.parameter_client import AsyncParameterClient

out = []
rclpy.init()
server = Node("param_server")
server.declare_parameter("speed", 1.5)
server.declare_parameter("mode", "auto", ParameterDescriptor(read_only=True))
server.declare_parameter("count", 3, ParameterDescriptor(integer_range=[IntegerRange(from_value=0, to_value=5)]))
server.declare_parameter("nested.a", [1, 2])
server.declare_parameter("typed_only", Parameter.Type.INTEGER)
user = Node("param_user")
ex = SingleThreadedExecutor()
ex.add_node(server)
ex.add_node(user)
client = AsyncParameterClient(user, "param_server")
out.append(["wait_for_services", client.wait_for_services(timeout_sec=5.0)])


def run(future):
    ex.spin_until_future_complete(future, timeout_sec=5)
    return future.result()


r = run(client.list_parameters())
out.append(["list", [sorted(r.result.names), sorted(r.result.prefixes)]])
r = run(client.list_parameters(["nested"], 1))
out.append(["list prefix", sorted(r.result.names)])
r = run(client.get_parameters(["speed", "mode", "nested.a"]))
out.append(["get", [parameter_value_to_python(v) for v in r.values]])
r = run(client.get_parameters(["speed", "missing"]))
out.append(["get with unknown", len(r.values)])
r = run(client.get_parameters(["speed", "typed_only"]))
out.append(["get uninitialized", len(r.values)])
r = run(client.get_parameter_types(["speed", "typed_only"]))
out.append(["types with uninitialized", list(r.types)])
r = run(client.get_parameter_types(["speed", "count", "missing"]))
out.append(["types", list(r.types)])
r = run(client.describe_parameters(["mode", "count"]))
out.append(["describe", [[d.name, d.type, d.read_only, len(d.integer_range)] for d in r.descriptors]])
r = run(client.set_parameters([Parameter("speed", value=2.5), Parameter("mode", value="manual"),
                                Parameter("count", value=9), Parameter("speed", value="fast")]))
out.append(["set", [[x.successful, x.reason] for x in r.results]])
r = run(client.set_parameters_atomically([Parameter("speed", value=3.5), Parameter("count", value=4)]))
out.append(["set atomically", [r.result.successful, r.result.reason]])
out.append(["values after", [server.get_parameter("speed").value, server.get_parameter("count").value]])
r = run(client.delete_parameters(["nested.a", "speed"]))
out.append(["delete", [[x.successful, x.reason] for x in r.results]])
r = run(client.set_parameters([Parameter("undeclared", value=1)]))
out.append(["set undeclared", [[x.successful, x.reason] for x in r.results]])
server.destroy_node()
user.destroy_node()
rclpy.shutdown()
print(json.dumps(out))
