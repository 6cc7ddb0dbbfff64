import json, sys, rclpy
from rclpy.node import Node
args = json.loads(sys.argv[1]); nodes = json.loads(sys.argv[2])
rclpy.init(args=["x", "--ros-args", *args])
out = []
for name, ns in nodes:
    n = Node(name, namespace=ns, automatically_declare_parameters_from_overrides=True)
    ps = {k: v.value for k, v in n.get_parameters_by_prefix("").items() if k not in ("use_sim_time", "start_type_description_service")}
    out.append({"name": n.get_name(), "ns": n.get_namespace(), "params": ps,
                "chatter": n.resolve_topic_name("chatter")})
    n.destroy_node()
print(json.dumps(out))
rclpy.shutdown()
