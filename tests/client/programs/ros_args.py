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
            "/robots/listener:\n  ros__parameters:\n    shared: 3\n"
            # a node key given twice in one file adds to its first place, as rcl's parser reads it
            "/**:\n  ros__parameters:\n    again: 4\n"
            "talker:\n  ros__parameters:\n    label: early\n    more: 5\n")
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
                                 "linear_scale.y", "linear_scale.on", "again", "more")])
listener = Node("listener", automatically_declare_parameters_from_overrides=True)
out.append(["listener", describe(listener, "shared", "rate", "label", "again", "more")])
local = Node("local", cli_args=["--ros-args", "-r", "__node:=renamed", "-p", "shared:=9", "-r", "chatter:=mine"],
             automatically_declare_parameters_from_overrides=True)
out.append(["cli_args", describe(local, "shared", "rate")])
isolated = Node("isolated", cli_args=["--ros-args", "-p", "own:=1"], use_global_arguments=False,
                automatically_declare_parameters_from_overrides=True)
out.append(["no global arguments", describe(isolated, "shared", "own")])
out.append(["remove_ros_args", remove_ros_args(["prog", "a", "--ros-args", "-p", "x:=1", "--",
                                                                "b"])])

from rclpy.context import Context  # noqa: E402
from rclpy.impl.implementation_singleton import rclpy_implementation as _rclpy  # noqa: E402
from rclpy.signals import get_current_signal_handlers_options  # noqa: E402
from rpyutils import add_dll_directories_from_env, import_c_library  # noqa: E402


def failure(fn, prefix_only=False):
    """The error's type (as rclpy's binding exposes them) and message; rcl's own parser words only by prefix."""
    try:
        fn()
        return "no error"
    except Exception as e:
        kinds = [k for k in ("RCLError", "RCLInvalidROSArgsError", "UnknownROSArgsError")
                 if isinstance(e, getattr(_rclpy, k))]
        text = str(e)
        return [kinds if kinds else type(e).__name__, text.split(":")[0] if prefix_only else text,
                "not-a-remap" in text or "--log-level" in text or "bogus" in text]


out.append(["bad cli_args", [
    failure(lambda: Node("bad_remap", cli_args=["--ros-args", "-r", "not-a-remap"]), prefix_only=True),
    failure(lambda: Node("bad_level", cli_args=["--ros-args", "--log-level", "bogus"]), prefix_only=True),
    failure(lambda: Node("unknown", cli_args=["--ros-args", "--my-flag", "-r", "a:=b", "extra"])),
]])
out.append(["rcl's other flags", failure(lambda: Node("flags", cli_args=[
    "--ros-args", "--log-file-name", "mine", "-e", "/enclave", "--enable-external-lib-logs", "--log-level",
    "flags:=debug"]).destroy_node())])
out.append(["bad init args", [
    failure(lambda: rclpy.init(context=Context(), args=["prog", "--ros-args", "unknown", "-x"])),
    failure(lambda: rclpy.init(context=Context(), args=["prog", "--ros-args", "-r"]), prefix_only=True),
    failure(lambda: rclpy.init(context=Context(), args=["prog", "Ragnar\udcc3\udcb6k"])),
]])
# rcl's remap grammar: names of letters, digits and '_' (no '__' inside, no leading digit), no wildcard, no empty
# or trailing slash in a name, an absolute namespace, a single ':='.
REMAPS = ["a:=b:=c", "__node:=a b", "__ns:=rel", "__ns:=/a/", "__ns:=//a", "foo:=", "a/:=b", "a:=/b/", "*:=x",
          "a:=~/c", "~/x:=y", "a:=1b", "a__b:=c", "__node:=_x", "n:rostopic://a:=b", "rostopic://__node:=x",
          "rosparam://a:=b", "n:m:a:=b", "a:=b c", "a.b:=c"]


# -p: a plain node name, a name of tokens joined by '.' or '/', a YAML scalar or a list of one type; -e absolute.
PARAMS = ["a.b/c:=1", "a..b:=1", "*:a:=1", "/ns/n:a:=1", "a:=", "a:= ", "a:=b:=c", "1a:=1", "a:=[1,2", "a:={x: 1}",
          "n:m:a:=1", "a:=[1, 2.0]", "a:=[a, 1]", "a:=[]", "a:=~"]
ENCLAVES = ["/", "/a/b", "/x/", "bad", "/1a"]


def rule_verdict(rule, flag="-r"):
    context = Context()
    try:
        context.init(["prog", "--ros-args", flag, rule])
    except Exception as e:
        return [k for k in ("RCLError", "RCLInvalidROSArgsError") if isinstance(e, getattr(_rclpy, k))] or str(e)
    context.try_shutdown()
    return "ok"


out.append(["remap grammar", [[rule, rule_verdict(rule)] for rule in REMAPS]])
out.append(["parameter rule grammar", [[rule, rule_verdict(rule, "-p")] for rule in PARAMS]])
out.append(["enclaves", [[name, rule_verdict(name, "-e")] for name in ENCLAVES]])
out.append(["signal handlers while initialised", str(get_current_signal_handlers_options())])
for n in (talker, listener, local, isolated):
    n.destroy_node()
rclpy.shutdown()
out.append(["signal handlers after shutdown", str(get_current_signal_handlers_options())])
with add_dll_directories_from_env("PATH") as handles:
    out.append(["rpyutils", [handles, import_c_library("_json").__name__, import_c_library(".decoder", "json").__name__,
                             failure(lambda: import_c_library("_no_such_extension_here"))[0]]])
print(json.dumps(out))
