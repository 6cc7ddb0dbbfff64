# --ros-args as rclpy resolves them: remaps, __node/__ns, node-prefixed rules, parameter files and -p in
# command-line order, a node's own cli_args over the process's.
import json
import os
import sys
import tempfile

import rclpy
from rclpy.node import Node
from rclpy.utilities import remove_ros_args

params = os.path.join(tempfile.mkdtemp(), "params.yaml")
with open(params, "w") as f:
    f.write("/**:\n  ros__parameters:\n    shared: 1\n    rate: 5.0\n"
            "talker:\n  ros__parameters:\n    rate: 10.0\n    nested:\n      gain: 2\n"
            # scalars typed as rcl types them (PyYAML's YAML 1.1 rules differ on several)
            "    tiny: 1e-9\n    hexa: 0x10\n    octal: 010\n    word: Yes\n    quoted: '1e-9'\n"
            "    big: 99999999999999999999\n    under: 1_000\n    covariance: [1e-9, 2E-3, .inf]\n"
            "    odom0_config:\n      - [true, false,\n         true]\n"
            # keys are names, whatever words they are (interactive_marker_twist_server's linear_scale: {x, y})
            "    linear_scale:\n      x: 1.0\n      y: 2.0\n      on: 3\n"
            "/robots/listener:\n  ros__parameters:\n    shared: 3\n")
rclpy.init(args=[sys.argv[0], "--ros-args", "-r", "chatter:=talk", "-r", "listener:__ns:=/robots",
                 "--params-file", params, "-p", "shared:=2", "-p", "talker:label:=mine", "-p", "talker:exp:=1e-3",
                 "-r", "renamed_later:__node:=never", "--log-level", "info"])
out = []


def describe(node, *names):
    values = {}
    for n in names:
        values[n] = node.get_parameter(n).value if node.has_parameter(n) else "undeclared"
    return [node.get_fully_qualified_name(), node.resolve_topic_name("chatter"),
            node.resolve_topic_name("~/private"), values]


talker = Node("talker", automatically_declare_parameters_from_overrides=True)
out.append(["talker", describe(talker, "shared", "rate", "nested.gain", "label", "tiny", "hexa", "octal", "word",
                                 "quoted", "big", "under", "covariance", "odom0_config", "exp",
                                 "linear_scale.y", "linear_scale.on")])
listener = Node("listener", automatically_declare_parameters_from_overrides=True)
out.append(["listener", describe(listener, "shared", "rate", "label")])
local = Node("local", cli_args=["--ros-args", "-r", "__node:=renamed", "-p", "shared:=9", "-r", "chatter:=mine"],
             automatically_declare_parameters_from_overrides=True)
out.append(["cli_args", describe(local, "shared", "rate")])
isolated = Node("isolated", cli_args=["--ros-args", "-p", "own:=1"], use_global_arguments=False,
                automatically_declare_parameters_from_overrides=True)
out.append(["no global arguments", describe(isolated, "shared", "own")])
out.append(["remove_ros_args", remove_ros_args(["prog", "a", "--ros-args", "-p", "x:=1", "--",
                                                                "b"])])
for n in (talker, listener, local, isolated):
    n.destroy_node()
rclpy.shutdown()
print(json.dumps(out))
