"""`diffctl param list|get|set|describe|dump|load`: the `ros2 param` counterpart, over any node's parameter services.

Output follows ros2param (Jazzy): `get` says the type ("Double value is: 0.5"), `dump` prints the YAML that
`load` and `--params-file` read, `set` and `load` report each parameter's success or the node's reason.
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Any

import click
import yaml

from diffctl.bus.graph import Graph
from diffctl.cli import bus_common as bc
from diffctl.client.interfaces import cls
from diffctl.client.parameter import Parameter, from_python_value, get_parameter_value, parameter_value_to_python
from diffctl.console import console
from diffctl.errors import BusError, ConfigError, suggest, yaml_error

RCL = "rcl_interfaces/srv/"
_GET_WORDS = {
    "bool": "Boolean value is:",
    "integer": "Integer value is:",
    "double": "Double value is:",
    "string": "String value is:",
    "byte_array": "Byte values are:",
    "bool_array": "Boolean values are:",
    "integer_array": "Integer values are:",
    "double_array": "Double values are:",
    "string_array": "String values are:",
}
_DESCRIBE_WORDS = {
    "not_set": "not set",
    "bool": "boolean",
    "integer": "integer",
    "double": "double",
    "string": "string",
    "byte_array": "byte array",
    "bool_array": "boolean array",
    "integer_array": "integer array",
    "double_array": "double array",
    "string_array": "string array",
}


def _kind(type_code: int) -> str:
    return Parameter.Type(int(type_code)).name.lower()


class _Remote:
    """Calls one node's parameter services from a CLI node (shared when one command asks several nodes)."""

    def __init__(
        self, node_name: str, timeout_s: float, *, graph: Graph | None = None, me: bc.ToolNode | None = None
    ) -> None:
        g = graph or bc.graph()
        nodes = g.nodes()
        self.fqn = bc.resolve_name(g, node_name, nodes, "node")
        if self.fqn not in nodes:
            raise ConfigError(
                f"unknown node {self.fqn}{suggest(self.fqn, nodes)}", hint="`diffctl node list` shows them"
            )
        self.timeout_s = timeout_s
        self._own = me is None
        self.me = me or bc.ToolNode(f"diffctl_param_{os.getpid()}")

    def call(self, short: str, srv: str, **request: Any) -> Any:
        """One call with the client's classes (the tool node spins on its own thread)."""
        node = self.me.node
        client = node.create_client(cls(RCL + srv), f"{self.fqn}/{short}")
        try:
            if not client.wait_for_service(self.timeout_s):
                raise BusError(
                    f"node {self.fqn} offers no {short} service",
                    hint="only nodes with parameter services answer `diffctl param`",
                )
            response = client.call(client.srv_type.Request(**request), timeout_sec=self.timeout_s)
            if response is None:
                raise BusError(f"node {self.fqn} did not answer {short} within {self.timeout_s:g} s")
            return response
        finally:
            node.destroy_client(client)

    def names(self) -> list[str]:
        return sorted(str(n) for n in self.call("list_parameters", "ListParameters").result.names)

    def values(self, names: list[str]) -> list[Any]:
        return list(self.call("get_parameters", "GetParameters", names=names).values)

    def close(self) -> None:
        if self._own:
            self.me.close()


def _remote(node_name: str, timeout_s: float) -> _Remote:
    return _Remote(node_name, timeout_s)


_TIMEOUT = click.option(
    "--timeout", type=float, default=5.0, show_default=True, help="Seconds to wait for the node's services."
)


@click.group()
def param() -> None:
    """Read and change any node's parameters.

    \b
    Example:
      diffctl param list /diff_drive_controller
      diffctl param set /diff_drive_controller linear.x.max_velocity 0.3
      diffctl param dump /controller_manager > cm.yaml
    """


@param.command("list")
@click.argument("node_name", required=False, metavar="[NODE]")
@click.option("--param-type", is_flag=True, help="Show each parameter's type.")
@click.option("--filter", "pattern", default=None, help="Only names matching this regular expression.")
@_TIMEOUT
def param_list(node_name: str | None, param_type: bool, pattern: str | None, timeout: float) -> None:
    """List the parameters of NODE, or of every node.

    \b
    Example:
      diffctl param list /controller_manager --param-type
    """
    try:
        regex = re.compile(pattern) if pattern else None
    except re.error as e:
        raise ConfigError(f"--filter {pattern!r} is not a regular expression: {e}") from None
    g = bc.graph()
    me = bc.ToolNode(f"diffctl_param_{os.getpid()}")
    targets = [node_name] if node_name else [n for n in g.nodes() if n != me.fqn]
    for target in targets:
        remote = _Remote(target, timeout, graph=g, me=me)
        try:
            try:
                names = [n for n in remote.names() if regex is None or regex.search(n)]
            except BusError:
                if node_name:
                    raise
                continue  # a node without parameter services: ros2 param list skips it too
            if not node_name:
                console.print(f"{remote.fqn}:", markup=False)
            kinds = (
                list(remote.call("get_parameter_types", "GetParameterTypes", names=names).types)
                if param_type and names
                else []
            )
            for i, n in enumerate(names):
                suffix = f" (type: {_kind(kinds[i])})" if param_type and kinds else ""
                console.print(f"  {n}{suffix}", markup=False)
        finally:
            remote.close()
    me.close()


@param.command("get")
@click.argument("node_name", metavar="NODE")
@click.argument("name")
@click.option("--hide-type", is_flag=True, help="Print only the value.")
@_TIMEOUT
def param_get(node_name: str, name: str, hide_type: bool, timeout: float) -> None:
    """Print the value of parameter NAME of NODE.

    \b
    Example:
      diffctl param get /diff_drive_controller wheel_separation
    """
    remote = _remote(node_name, timeout)
    try:
        values = remote.values([name])
        if not values or values[0].type == Parameter.Type.NOT_SET.value:
            console.print("Parameter not set.", markup=False)
            return
        kind = _kind(values[0].type)
        text = _show(parameter_value_to_python(values[0]))
        console.print(text if hide_type else f"{_GET_WORDS[kind]} {text}", markup=False)
    finally:
        remote.close()


def _show(value: Any) -> str:
    if isinstance(value, list) and value and isinstance(value[0], bytes):
        return str([b[0] for b in value])
    return str(value)


# A negative VALUE (-2.0) is a value, as `ros2 param set` takes it, not an unknown option.
@param.command("set", context_settings={"ignore_unknown_options": True})
@click.argument("node_name", metavar="NODE")
@click.argument("name")
@click.argument("value")
@_TIMEOUT
def param_set(node_name: str, name: str, value: str, timeout: float) -> None:
    """Set parameter NAME of NODE to VALUE (YAML: 1 is an integer, 1.0 a double, [a, b] a list).

    \b
    Example:
      diffctl param set /diff_drive_controller linear.x.max_velocity 0.3
    """
    msg_value = get_parameter_value(value)  # ros2param's reading of VALUE
    remote = _remote(node_name, timeout)
    try:
        parameter = cls("rcl_interfaces/msg/Parameter")(name=name, value=msg_value)
        resp = remote.call("set_parameters", "SetParameters", parameters=[parameter])
        result = resp.results[0]
        if not result.successful:
            raise BusError(
                f"Setting parameter failed: {result.reason}" if result.reason else "Setting parameter failed"
            )
        console.print("Set parameter successful", markup=False)
    finally:
        remote.close()


@param.command("describe")
@click.argument("node_name", metavar="NODE")
@click.argument("names", nargs=-1, required=True, metavar="NAME...")
@_TIMEOUT
def param_describe(node_name: str, names: tuple[str, ...], timeout: float) -> None:
    """Show the type, description and constraints of parameters of NODE.

    \b
    Example:
      diffctl param describe /diff_drive_controller wheel_separation publish_rate
    """
    remote = _remote(node_name, timeout)
    try:
        resp = remote.call("describe_parameters", "DescribeParameters", names=list(names))
        if not resp.descriptors:
            raise ConfigError(
                f"node {remote.fqn} has no parameter named {' or '.join(names)}",
                hint=f"`diffctl param list {remote.fqn}` shows them",
            )
        for msg in resp.descriptors:
            for line in _describe_lines(msg):
                console.print(line, markup=False)
    finally:
        remote.close()


def _describe_lines(d: Any) -> list[str]:
    """ros2param's describe of an rcl_interfaces/msg/ParameterDescriptor."""
    out = [f"Parameter name: {d.name}", f"  Type: {_DESCRIBE_WORDS[_kind(d.type)]}"]
    if d.description:
        out.append(f"  Description: {d.description}")
    constraints = []
    if d.read_only:
        constraints.append("    Read only: true")
    if d.dynamic_typing:
        constraints.append("    Dynamic typing: true")
    for rng in (*d.floating_point_range, *d.integer_range):
        constraints += [f"    Min value: {rng.from_value}", f"    Max value: {rng.to_value}"]
        if rng.step:
            constraints.append(f"    Step: {rng.step}")
    if d.additional_constraints:
        constraints.append(f"    {d.additional_constraints}")
    if constraints:
        out += ["  Constraints:", *constraints]
    return out


def nest(flat: dict[str, Any]) -> dict[str, Any]:
    """Dotted names as nested maps (`a.b: 1` → `a: {b: 1}`), as `ros2 param dump` writes them."""
    out: dict[str, Any] = {}
    for name in sorted(flat):
        *parents, leaf = name.split(".")
        level = out
        for p in parents:
            nxt = level.setdefault(p, {})
            if not isinstance(nxt, dict):  # `a` and `a.b` both exist: keep the dotted name flat
                level, leaf = out, name
                break
            level = nxt
        level[leaf] = flat[name]
    return out


@param.command("dump")
@click.argument("node_name", metavar="NODE")
@click.option(
    "--output",
    "output",
    type=click.Path(dir_okay=False),
    default=None,
    help="Write the YAML to this file instead of standard output.",
)
@_TIMEOUT
def param_dump(node_name: str, output: str | None, timeout: float) -> None:
    """Print NODE's parameters as a parameter file (`load` and `--params-file` read it back).

    \b
    Example:
      diffctl param dump /diff_drive_controller > ddc.yaml
    """
    remote = _remote(node_name, timeout)
    try:
        names = remote.names()
        values = remote.values(names) if names else []
        flat = {n: parameter_value_to_python(v) for n, v in zip(names, values, strict=False)}
        flat = {
            n: ([b[0] for b in v] if isinstance(v, list) and v and isinstance(v[0], bytes) else v)
            for n, v in flat.items()
            if v is not None
        }
        text = yaml.safe_dump({remote.fqn: {"ros__parameters": nest(flat)}}, sort_keys=True, default_flow_style=False)
    finally:
        remote.close()
    if output:
        Path(output).write_text(text)
    else:
        console.print(text.rstrip(), markup=False, soft_wrap=True)


@param.command("load")
@click.argument("node_name", metavar="NODE")
@click.argument("file", type=click.Path(dir_okay=False))
@click.option("--no-use-wildcard", is_flag=True, help="Ignore the `/**` section of FILE.")
@_TIMEOUT
def param_load(node_name: str, file: str, no_use_wildcard: bool, timeout: float) -> None:
    """Set NODE's parameters from a parameter file (its section for NODE, and `/**`).

    \b
    Example:
      diffctl param load /diff_drive_controller ddc.yaml
    """
    remote = _remote(node_name, timeout)
    try:
        values = _file_values(file, remote.fqn, not no_use_wildcard)
        if not values:
            raise ConfigError(
                f"no parameters for {remote.fqn} in the file",
                source=file,
                hint=f"sections are node names ({remote.fqn}) or /**, each with ros__parameters",
            )
        params = []
        for name, value in values.items():
            try:
                params.append(from_python_value(name, value).to_parameter_msg())
            except (TypeError, ValueError) as e:
                raise ConfigError(f"parameter '{name}': {e}", source=file) from None
        resp = remote.call("set_parameters", "SetParameters", parameters=params)
        # As ros2 param load: each parameter's outcome, and refusals (a dump's read-only parameters) are
        # reported, not fatal.
        for p, result in zip(params, resp.results, strict=False):
            if result.successful:
                console.print(f"Set parameter {p.name} successful", markup=False)
            else:
                console.print(
                    f"Set parameter {p.name} failed" + (f": {result.reason}" if result.reason else ""), markup=False
                )
    finally:
        remote.close()


def _file_values(path: str, fqn: str, wildcard: bool) -> dict[str, Any]:
    """The parameters a params file gives node `fqn`: `/**` first (if used), then its own section."""
    try:
        data = yaml.safe_load(Path(path).read_text())
    except FileNotFoundError:
        raise ConfigError("parameter file not found", source=path) from None
    except (OSError, UnicodeDecodeError) as e:
        raise ConfigError(f"cannot read the parameter file: {e}", source=path) from None
    except yaml.YAMLError as e:
        raise yaml_error(e, path) from None
    if not isinstance(data, dict):
        raise ConfigError("a parameter file must be a mapping of node names to ros__parameters", source=path)
    out: dict[str, Any] = {}
    for key, section in data.items():
        key = "/" + str(key).lstrip("/")
        if not isinstance(section, dict) or "ros__parameters" not in section:
            continue
        # A bare `name:` section means that node in the root namespace, as rcl reads it.
        if (key == "/**" and wildcard) or key == fqn:
            out.update(flatten(section["ros__parameters"] or {}))
    return out


def flatten(d: dict[str, Any], prefix: str = "") -> dict[str, Any]:
    """Nested maps as dotted names, the inverse of `nest`."""
    out: dict[str, Any] = {}
    for k, v in d.items():
        if isinstance(v, dict):
            out.update(flatten(v, f"{prefix}{k}."))
        else:
            out[f"{prefix}{k}"] = v
    return out
