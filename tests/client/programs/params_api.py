# Parameter API results and exceptions, as a user observes them (run under the real rclpy and diffctl).
import json

import rclpy
from rcl_interfaces.msg import FloatingPointRange, IntegerRange, ParameterDescriptor
from rclpy.node import Node
from rclpy.parameter import Parameter

out = []


def obs(label, fn):
    try:
        value = fn()
        value = [_show(v) for v in value] if isinstance(value, list) else _show(value)
        out.append([label, "ok", value])
    except Exception as e:
        out.append([label, type(e).__name__, str(e)])


def _show(v):
    if isinstance(v, Parameter):
        return [v.name, v.type_.name, _plain(v.value)]
    if hasattr(v, "successful"):
        return [v.successful, v.reason]
    if hasattr(v, "names") and hasattr(v, "prefixes"):
        return [sorted(v.names), sorted(v.prefixes)]
    if isinstance(v, dict):
        return {k: _show(x) for k, x in sorted(v.items())}
    return _plain(v)


def _plain(v):
    if isinstance(v, (list, tuple)) or type(v).__name__ == "array":
        return [_plain(x) for x in v]
    if isinstance(v, bytes):
        return list(v)
    if hasattr(v, "name") and hasattr(v, "value") and not isinstance(v, (int, float, str)):
        return str(v)
    return v


rclpy.init(args=["prog", "--ros-args", "-p", "from_cli:=5", "-p", "d:=3", "-p", "s:=hello",
                 "-p", "arr:=[1, 2, 3]"])
node = Node("params_demo")
log = []
obs("declare int", lambda: node.declare_parameter("i", 1))
obs("declare override", lambda: node.declare_parameter("from_cli", 0))
obs("declare wrong override type", lambda: node.declare_parameter("d", 1.0))
obs("declare string override", lambda: node.declare_parameter("s", "x"))
obs("declare int array override", lambda: node.declare_parameter("arr", [0]))
obs("declare twice", lambda: node.declare_parameter("i", 2))
obs("declare empty list", lambda: node.declare_parameter("empty", []))
obs("declare typed", lambda: node.declare_parameter("typed", Parameter.Type.DOUBLE))
obs("get uninitialized", lambda: node.get_parameter("typed"))
obs("declare read only", lambda: node.declare_parameter("ro", "fixed", ParameterDescriptor(read_only=True)))
rng = ParameterDescriptor(integer_range=[IntegerRange(from_value=0, to_value=10, step=2)])
obs("declare ranged", lambda: node.declare_parameter("r2", 4, rng))
obs("declare out of range", lambda: node.declare_parameter("r3", 11, ParameterDescriptor(
    integer_range=[IntegerRange(from_value=0, to_value=10, step=1)])))
frng = ParameterDescriptor(floating_point_range=[FloatingPointRange(from_value=0.0, to_value=1.0, step=0.25)])
obs("declare float ranged", lambda: node.declare_parameter("f", 0.5, frng))
both = ParameterDescriptor(integer_range=[IntegerRange(from_value=0, to_value=10, step=1)],
                           floating_point_range=[FloatingPointRange(from_value=0.0, to_value=1.0, step=0.0)])
obs("declare both ranges", lambda: node.declare_parameter("both", 5, both))
obs("set both ranges out", lambda: node.set_parameters([Parameter("both", value=11)]))
obs("describe both ranges", lambda: [[len(d.integer_range), len(d.floating_point_range)]
                                     for d in node.describe_parameters(["both"])])
obs("declare dynamic", lambda: node.declare_parameter("dyn", 1, ParameterDescriptor(dynamic_typing=True)))
obs("declare bad name", lambda: node.declare_parameter("bad..name", 1))
obs("get undeclared", lambda: node.get_parameter("nope"))
obs("has", lambda: [node.has_parameter("i"), node.has_parameter("nope")])
obs("set ok", lambda: node.set_parameters([Parameter("i", value=3)]))
obs("set wrong type", lambda: node.set_parameters([Parameter("i", value="three")]))
obs("set read only", lambda: node.set_parameters([Parameter("ro", value="other")]))
obs("set out of range", lambda: node.set_parameters([Parameter("r2", value=12)]))
obs("set bad step", lambda: node.set_parameters([Parameter("r2", value=5)]))
obs("set range edge", lambda: node.set_parameters([Parameter("r2", value=10)]))
obs("set float step", lambda: node.set_parameters([Parameter("f", value=0.3)]))
obs("set float edge", lambda: node.set_parameters([Parameter("f", value=1.0)]))
obs("set dynamic to string", lambda: node.set_parameters([Parameter("dyn", value="now a string")]))
obs("set undeclared", lambda: node.set_parameters([Parameter("undeclared", value=1)]))
obs("set atomically mixed", lambda: node.set_parameters_atomically(
    [Parameter("i", value=4), Parameter("ro", value="x")]))
obs("value after failed atomic", lambda: node.get_parameter("i"))
obs("unset static", lambda: node.set_parameters([Parameter("i", Parameter.Type.NOT_SET)]))
obs("by prefix", lambda: node.declare_parameters("grp", [("a", 1), ("b", "two"), ("c.d", 3.0)]))
obs("get by prefix", lambda: node.get_parameters_by_prefix("grp"))
obs("list depth 1", lambda: node.list_parameters(["grp"], 1))
obs("list all", lambda: node.list_parameters([], 0))
obs("undeclare read only", lambda: node.undeclare_parameter("ro"))
obs("undeclare", lambda: node.undeclare_parameter("grp.a"))
obs("undeclare missing", lambda: node.undeclare_parameter("grp.a"))
obs("types", lambda: [str(t) for t in node.get_parameter_types(["i", "s"])])
obs("describe", lambda: [[d.name, d.type, d.read_only] for d in node.describe_parameters(["ro", "i"])])
obs("describe missing", lambda: node.describe_parameter("nope"))
obs("use_sim_time", lambda: node.get_parameter("use_sim_time"))


def pre1(params):
    log.append("pre1")
    return params


def on(tag):
    def cb(params):
        log.append(tag)
        from rcl_interfaces.msg import SetParametersResult
        return SetParametersResult(successful=tag != "on_refuse" or params[0].value != 99,
                                   reason="refused 99" if tag == "on_refuse" else "")
    return cb


def post(tag):
    return lambda params: log.append(tag)


node.add_pre_set_parameters_callback(pre1)
node.add_on_set_parameters_callback(on("on1"))
node.add_on_set_parameters_callback(on("on2"))
node.add_post_set_parameters_callback(post("post1"))
node.add_post_set_parameters_callback(post("post2"))
obs("set with callbacks", lambda: node.set_parameters([Parameter("i", value=7)]))
obs("callback order", lambda: list(log))
refuse = on("on_refuse")
node.add_on_set_parameters_callback(refuse)
log.clear()
obs("refused by callback", lambda: node.set_parameters([Parameter("i", value=99)]))
obs("callback order refused", lambda: list(log))
node.remove_on_set_parameters_callback(refuse)
obs("remove unknown callback", lambda: node.remove_on_set_parameters_callback(refuse))
# rclpy's lists, which packages count before adding their own (the time source's use_sim_time one included)
obs("callback lists", lambda: [len(node._pre_set_parameters_callbacks), len(node._on_set_parameters_callbacks),
                               len(node._post_set_parameters_callbacks), refuse in node._on_set_parameters_callbacks])

auto = Node("auto_demo", parameter_overrides=[Parameter("x", value=2.5), Parameter("name", value="n")],
            automatically_declare_parameters_from_overrides=True)
obs("auto declared", lambda: [auto.get_parameter("x"), auto.get_parameter("name"), auto.get_parameter("from_cli")])
loose = Node("loose_demo", allow_undeclared_parameters=True)
obs("undeclared allowed get", lambda: loose.get_parameter("free"))
obs("undeclared allowed set", lambda: loose.set_parameters([Parameter("free", value=1)]))
obs("undeclared allowed after", lambda: loose.get_parameter("free"))
cli = Node("cli_demo", cli_args=["--ros-args", "-p", "k:=true"])
obs("cli_args override", lambda: cli.declare_parameter("k", False))
import os  # noqa: E402
import tempfile  # noqa: E402

from rclpy.parameter import parameter_dict_from_yaml_file, parameter_value_to_python  # noqa: E402

yaml_path = os.path.join(tempfile.mkdtemp(), "p.yaml")
with open(yaml_path, "w") as f:
    f.write("/**:\n  ros__parameters:\n    w: 1\nnode_a:\n  ros__parameters:\n    a: 1\n"
            "    b: {c: [1.5, 2.0], d: hi, e: true}\n")
obs("parameter_dict_from_yaml_file", lambda: {k: [v.name, v.value.type, _plain(parameter_value_to_python(v.value))]
                                              for k, v in parameter_dict_from_yaml_file(yaml_path).items()})
obs("with wildcard", lambda: sorted(parameter_dict_from_yaml_file(yaml_path, use_wildcard=True,
                                                                  target_nodes=["node_a"])))
obs("missing target", lambda: parameter_dict_from_yaml_file(yaml_path, target_nodes=["other"]))
for n in (node, auto, loose, cli):
    n.destroy_node()
rclpy.shutdown()
obs("shutdown twice", lambda: rclpy.shutdown())
print(json.dumps(out))
