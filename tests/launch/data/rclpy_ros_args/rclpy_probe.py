"""Run in a venv with ROS 2 Jazzy's real rclpy (tests/oracle/jazzy_venv.py): for each case of cases.json (argv[1],
with {data} replaced by argv[2]), every node's name, namespace, parameter overrides and resolved `chatter`,
as a JSON list of lists on stdout."""

import json
import sys

import rclpy
from rclpy.node import Node

with open(sys.argv[1]) as f:
    cases = json.load(f)["cases"]
results = []
for case in cases:
    args = [a.replace("{data}", sys.argv[2]) for a in case["ros_args"]]
    rclpy.init(args=["probe", "--ros-args", *args])
    out = []
    for name, ns in case["nodes"]:
        local = [a.replace("{data}", sys.argv[2]) for a in case.get("local", [])]  # the node's own (cli_args)
        n = Node(name, namespace=ns, automatically_declare_parameters_from_overrides=True,
                 cli_args=["--ros-args", *local] if local else None)
        ps = {k: v.value for k, v in n.get_parameters_by_prefix("").items()
              if k not in ("use_sim_time", "start_type_description_service")}
        ps = {k: list(v) if not isinstance(v, (str, bytes)) and hasattr(v, "__len__") else v for k, v in ps.items()}
        out.append({"name": n.get_name(), "ns": n.get_namespace(), "params": ps,
                    "chatter": n.resolve_topic_name("chatter")})
        n.destroy_node()
    rclpy.shutdown()
    results.append(out)
print(json.dumps(results))
