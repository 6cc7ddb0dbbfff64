"""ROS-style `--ros-args` on the command line of every component, resolved as rcl and rclcpp resolve them.

The launcher writes a node's parameters to a YAML file and starts it with
`--ros-args -r __node:=NAME -r __ns:=/NS --params-file FILE -p name:=value -r from:=to`; components read
them back with `current()`. `diffctl.cli.main` strips the `--ros-args ... [--]` span from argv before
click parses the rest, so every command accepts it without declaring it.

This module is the one resolution path of every node's name, namespace, remappings and parameter overrides
(a process's own node, the controllers a manager hosts, the rclpy-compatible client):

- `parse(argv, default_name, default_namespace, local_argv=…)` → `RosArgs` for one node. `local_argv` are a
  node's own arguments (rclcpp's NodeOptions.arguments, a controller's `node_options_args`), `argv` the
  process's (global) ones.
- Parameters (rcl_arguments_get_param_overrides + rclcpp's parameter_map_from): `--params-file` files and
  `-p [node:]name:=value` rules are read in command-line order into one table of node keys (`/**`,
  `/robot1/controller_manager`, `talker`, …), each key kept at the place it first appeared and each value
  overwritten in place; a node takes, in that key order, every key whose pattern matches its fully qualified
  name (`/*` one name, `/**` any number, a key without a leading slash is `/key`). `-p name:=v` goes under
  `/**`, `-p talker:name:=v` under `talker`. Local arguments override global ones.
- Remapping (rcl_remap_*): the first matching rule wins, local rules before global ones; `talker:chatter:=x`
  applies only to the node named talker (`talker:__node:=` / `talker:__ns:=` to the node created as talker).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from diffctl.errors import ConfigError, yaml_error

_current: list[str] = []


@dataclass(frozen=True)
class RemapRule:
    """`-r [node:]match:=replacement`; `node` limits the rule to the node of that name."""

    match: str
    replacement: str
    node: str | None = None

    def applies_to(self, node_name: str | None) -> bool:
        return self.node is None or self.node == node_name


class ParameterOverrides:
    """rcl's table of parameter overrides: node keys in the order they first appeared, each with its parameters
    in the order they first appeared; a later file or `-p` overwrites a value in place."""

    def __init__(self) -> None:
        self.entries: dict[str, dict[str, Any]] = {}

    def set(self, node_key: str, name: str, value: Any) -> None:
        self.entries.setdefault(node_key, {})[name] = value

    def add_file(self, path: str | Path) -> None:
        for key, params in _file_sections(path):
            entry = self.entries.setdefault(key, {})
            entry.update(params)

    def for_node(self, fqn: str) -> dict[str, Any]:
        """The overrides of the node whose fully qualified name is `fqn` (rclcpp's parameter_map_from)."""
        out: dict[str, Any] = {}
        for key, params in self.entries.items():
            if node_key_matches(key, fqn):
                out.update(params)
        return out


@dataclass(frozen=True)
class RosArgs:
    """One node's view of `--ros-args`: its resolved name and namespace (None when not remapped), the
    parameters that apply to it, and the remappings of its topics and services (first rule wins)."""

    node_name: str | None = None
    namespace: str | None = None
    params: dict[str, Any] = field(default_factory=dict)
    remaps: dict[str, str] = field(default_factory=dict)
    params_files: tuple[str, ...] = ()
    log_level: str | None = None
    remap_rules: tuple[RemapRule, ...] = ()  # every rule, in order (local ones first), prefixed ones included
    overrides: ParameterOverrides = field(default_factory=ParameterOverrides)  # global, then local layers merged

    def param(self, name: str, default: Any = None) -> Any:
        return self.params.get(name, default)


_NAME_CHAR = "[A-Za-z0-9_]"


def node_fqn(name: str, namespace: str | None = "/") -> str:
    """`/ns/name` of a node (a name already starting with `/` is taken as fully qualified)."""
    if name.startswith("/"):
        return name
    ns = (namespace or "/").rstrip("/")
    if ns and not ns.startswith("/"):
        ns = "/" + ns
    return f"{ns}/{name}"


def _key_regex(key: str) -> str:
    # rclcpp: "/*" → one name, "/**" → any number of names; the rest literally
    out, i = [], 0
    while i < len(key):
        if key.startswith("/**", i):
            out.append(f"(/{_NAME_CHAR}+)*")
            i += 3
        elif key.startswith("/*", i):
            out.append(f"(/{_NAME_CHAR}+)")
            i += 2
        else:
            out.append(re.escape(key[i]))
            i += 1
    return "".join(out)


def node_key_matches(key: str, fqn: str) -> bool:
    """Whether a parameter file's node key (`/**`, `/*/talker`, `/ns/**`, `talker`, …) selects node `fqn`;
    a key without a leading slash is rooted (`talker` is `/talker` only)."""
    rooted = key if key.startswith("/") else "/" + key
    return re.fullmatch(_key_regex(rooted), fqn) is not None


def split_argv(argv: list[str]) -> tuple[list[str], list[str]]:
    """Split argv into (ordinary args, ros args); `--ros-args` spans up to `--` or the end, and may repeat."""
    plain: list[str] = []
    ros: list[str] = []
    i = 0
    while i < len(argv):
        if argv[i] == "--ros-args":
            i += 1
            while i < len(argv) and argv[i] != "--":
                if argv[i] != "--ros-args":  # rcl: a repeated flag inside ROS arguments just continues them
                    ros.append(argv[i])
                i += 1
            i += 1  # skip the closing "--"
            continue
        plain.append(argv[i])
        i += 1
    return plain, ros


def set_current(ros_argv: list[str]) -> None:
    global _current
    _current = list(ros_argv)


def current_argv() -> list[str]:
    """This process's `--ros-args` as given (for a command that passes them on, as `diffctl run` does)."""
    return list(_current)


def parse_value(text: str) -> Any:
    """A `-p name:=value` value, typed as rcl types it (rcl_parse_yaml_value: the params files' scalar rules)."""
    import yaml  # here, not at the top: every `diffctl` command imports this module, most never parse YAML

    try:
        return _load_yaml(text) if text != "" else ""
    except yaml.YAMLError:
        return text


_TRUE = frozenset(["Y", "y", "yes", "Yes", "YES", "true", "True", "TRUE", "on", "On", "ON"])
_FALSE = frozenset(["N", "n", "no", "No", "NO", "false", "False", "FALSE", "off", "Off", "OFF"])
_SPECIAL_FLOATS = {f"{sign}{dot}": float(f"{sign or '+'}{word}")
                   for sign in ("", "+", "-") for dot, word in
                   ((".inf", "inf"), (".Inf", "inf"), (".INF", "inf")) } | {
    n: float("nan") for n in (".nan", ".NaN", ".NAN")}
_C_INT = re.compile(r"^[ \t\n\v\f\r]*[+-]?(0[xX][0-9a-fA-F]+|0[0-7]*|[1-9][0-9]*)$")
_C_FLOAT = re.compile(r"^[ \t\n\v\f\r]*[+-]?(?:(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
                      r"|0[xX](?:[0-9a-fA-F]+\.?[0-9a-fA-F]*|\.[0-9a-fA-F]+)(?:[pP][+-]?[0-9]+)?"
                      r"|inf(?:inity)?|nan(?:\([0-9A-Za-z_]*\))?)$", re.IGNORECASE)
INT64_MIN, INT64_MAX = -(2**63), 2**63 - 1


def rcl_scalar(text: str) -> Any:
    """A plain (unquoted, untagged) YAML scalar as rcl_yaml_param_parser types it: its eleven true and false
    words, then what C's strtoll(base 0) reads whole (0x1F hex, 010 octal), then what strtod reads whole
    (1e-9, .5, inf, 0x1p3) or YAML's .inf/.nan, else the text. PyYAML's YAML 1.1 rules differ (1e-9 is a
    string there, 1_000 an int); a file ROS reads must load the same here."""
    if text in _TRUE:
        return True
    if text in _FALSE:
        return False
    if _C_INT.match(text):
        body = text.strip()
        sign = -1 if body.startswith("-") else 1
        digits = body.lstrip("+-")
        value = sign * (int(digits, 16) if digits[:2] in ("0x", "0X") else int(digits, 8) if digits.startswith("0")
                        else int(digits))
        if INT64_MIN <= value <= INT64_MAX:  # strtoll sets ERANGE beyond: rcl tries a double next
            return value
    if text in _SPECIAL_FLOATS:
        return _SPECIAL_FLOATS[text]
    if _C_FLOAT.match(text):
        body = text.strip()
        try:
            value = float.fromhex(body) if "x" in body.lower() and "n" not in body.lower() else float(body)
        except ValueError:
            return text
        if math.isinf(value) and "inf" not in body.lower():
            return text  # overflow: strtod's ERANGE, a string for rcl
        return value
    return text


def _rcl_loader(base: Any) -> Any:
    """`base` (a PyYAML safe loader) with rcl's typing of plain scalars; quoted or tagged scalars stay YAML's.
    An empty value stays None (rcl refuses it; diffctl's readers report it where the value is used)."""

    class RclLoader(base):
        def construct_undefined_plain(self, node: Any) -> Any:
            return rcl_scalar(node.value) if node.value != "" else None

        def construct_mapping(self, node: Any, deep: bool = False) -> Any:
            # A key is a name to rcl, never a value: `y:` under `linear_scale:` is "y", not true.
            for key, _ in node.value:
                if key.tag == "tag:diffctl,rcl-scalar":
                    key.tag = "tag:yaml.org,2002:str"
            names = [key.value for key, _ in node.value if isinstance(key.value, str)]
            if len(set(names)) == len(names):
                return super().construct_mapping(node, deep)
            # A key given twice (`/**:` heading two places of one file) adds to the first, as rcl's
            # event-driven parser reads it, where PyYAML would keep the last mapping alone.
            self.flatten_mapping(node)
            mapping: dict[Any, Any] = {}
            for key_node, value_node in node.value:
                _merge_into(mapping, self.construct_object(key_node, deep=True),
                            self.construct_object(value_node, deep=True))
            return mapping

    RclLoader.yaml_implicit_resolvers = {}  # every plain scalar resolves to the one tag below
    RclLoader.add_implicit_resolver("tag:diffctl,rcl-scalar", re.compile(r"(?s).*"), None)
    RclLoader.add_constructor("tag:diffctl,rcl-scalar", RclLoader.construct_undefined_plain)
    return RclLoader


def _merge_into(mapping: dict[Any, Any], key: Any, value: Any) -> None:
    if isinstance(mapping.get(key), dict) and isinstance(value, dict):
        for k, v in value.items():
            _merge_into(mapping[key], k, v)
    else:
        mapping[key] = value


_loaders: dict[str, Any] = {}


def _load_yaml(text: str) -> Any:
    """A params file or value as rcl reads it (rcl_scalar), through PyYAML's safe loading on libyaml's parser
    when PyYAML has it (8× faster on a controllers file: every node and controller reads its file at
    start-up); the error of bad input is the pure-Python parser's, the one with the line and column every
    other file of diffctl reports."""
    import yaml

    if not _loaders:
        _loaders["py"] = _rcl_loader(yaml.SafeLoader)
        if hasattr(yaml, "CSafeLoader"):
            _loaders["c"] = _rcl_loader(yaml.CSafeLoader)
    if "c" in _loaders:
        try:
            return yaml.load(text, Loader=_loaders["c"])
        except yaml.YAMLError:
            pass
    return yaml.load(text, Loader=_loaders["py"])


def _read_yaml_file(path: str | Path) -> Any:
    import yaml

    p = Path(path)
    try:
        data = _load_yaml(p.read_text()) or {}
    except FileNotFoundError:
        raise ConfigError("parameter file not found", source=str(p)) from None
    except (OSError, UnicodeDecodeError) as e:
        raise ConfigError(f"cannot read the parameter file: {e}", source=str(p)) from None
    except yaml.YAMLError as e:
        raise yaml_error(e, str(p)) from None
    if not isinstance(data, dict):
        raise ConfigError("a parameter file must be a mapping of node names to ros__parameters", source=str(p))
    return data


_sections_cache: dict[tuple[str, int, int, int, int], list[tuple[str, dict[str, Any]]]] = {}


def _file_sections(path: str | Path) -> list[tuple[str, dict[str, Any]]]:
    """(node key, flattened parameters) of every `ros__parameters` map in file order; keys nested above it
    join with `/` (`robot1: {controller_manager: {ros__parameters: …}}` is `robot1/controller_manager`), as
    rcl_yaml_param_parser reads them. A file read before and unchanged since (same size and modification time)
    is not parsed again: a controller manager's every controller node reads the manager's files."""
    try:
        st = Path(path).stat()
        key: tuple[str, int, int, int, int] | None = (
            str(Path(path).resolve()), st.st_ino, st.st_mtime_ns, st.st_ctime_ns, st.st_size)
    except OSError:
        key = None
    if key is not None and key in _sections_cache:
        return [(k, {n: list(v) if isinstance(v, list) else v for n, v in params.items()})
                for k, params in _sections_cache[key]]
    sections = _parse_sections(path)
    if key is not None:
        _sections_cache[key] = sections
        return _file_sections(path)
    return sections


def _parse_sections(path: str | Path) -> list[tuple[str, dict[str, Any]]]:
    out: list[tuple[str, dict[str, Any]]] = []

    def walk(d: dict[Any, Any], parts: list[str]) -> None:
        for key, value in d.items():
            key = str(key)
            if key == "ros__parameters":
                if parts:
                    out.append(("/".join(parts), _flatten(value or {}) if isinstance(value, dict) else {}))
            elif isinstance(value, dict):
                walk(value, [*parts, key])

    walk(_read_yaml_file(path), [])
    return out


def load_params_file(path: str | Path, node: str | None) -> dict[str, Any]:
    """The parameters a ROS params file gives node `node` (its fully qualified name; a bare name is a node at
    the root namespace), with rcl's key matching; every section's when `node` is None."""
    table = ParameterOverrides()
    table.add_file(path)
    if node is None:
        out: dict[str, Any] = {}
        for params in table.entries.values():
            out.update(params)
        return out
    return table.for_node(node_fqn(node))


def _flatten(d: dict[str, Any], prefix: str = "") -> dict[str, Any]:
    # Nested YAML maps become dotted names (linear: {x: {max_velocity: 1}} → linear.x.max_velocity), as rclcpp does.
    out: dict[str, Any] = {}
    for k, v in d.items():
        name = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(_flatten(v, name + "."))
        else:
            out[name] = _rcl_sequence(name, v) if isinstance(v, list) else v
    return out


def _rcl_sequence(name: str, value: list[Any]) -> list[Any]:
    """A sequence as rcl's event parser reads it: a sequence inside it adds its items to the same array, so
    `odom0_config: [[true, true, …]]` (a `- [ … ]` block item, common in robot_localization files) is the flat
    array; after that inner sequence ends rcl expects a key, so anything else nested is its error."""
    inner = [i for i, v in enumerate(value) if isinstance(v, list)]
    if not inner:
        return value
    if inner == [len(value) - 1] and not any(isinstance(v, (list, dict)) for v in value[-1]):
        return [*value[:-1], *value[-1]]
    raise ConfigError(f"parameter {name!r}: a sequence of sequences is not a parameter value ({value!r})",
                      hint="rcl reads one array per parameter: write the values as one list")


@dataclass
class _Parsed:
    rules: list[RemapRule] = field(default_factory=list)
    files: list[str] = field(default_factory=list)
    overrides: ParameterOverrides = field(default_factory=ParameterOverrides)
    log_level: str | None = None


# rcl's lexer: a name token is a letter or underscore then letters, digits and underscores, never two
# underscores in a row (those begin rcl's own `__node`/`__ns` words).
_TOKEN = r"(?!\w*__)[A-Za-z_]\w*"
_NAME = re.compile(rf"(?:/|~/)?{_TOKEN}(?:/{_TOKEN})*", re.ASCII)
_NAMESPACE = re.compile(rf"/(?:{_TOKEN}(?:/{_TOKEN})*/?)?", re.ASCII)
_NODE_NAME = re.compile(_TOKEN, re.ASCII)
_NODE_PREFIX = re.compile(rf"({_TOKEN}):(?!//)", re.ASCII)
_SCHEMES = ("rostopic://", "rosservice://")


def _remap_rule(rule: str) -> RemapRule:
    """`-r [node:][rostopic://|rosservice://]match:=replacement`, `[node:]__node:=name` or `[node:]__ns:=/ns`,
    checked as rcl's remap parser checks it (no wildcards or back-references, no empty or doubled slashes)."""
    def bad(why: str) -> ConfigError:
        return ConfigError(f"--ros-args: cannot parse remap rule {rule!r}: {why}",
                           hint="valid: [NODE:]FROM:=TO with names of letters, digits, '_' and '/' "
                                "(FROM may start '~/' or rostopic:// / rosservice://), __node:=NAME, __ns:=/NS")

    lhs, sep, rhs = rule.partition(":=")
    if not sep:
        raise bad("no ':='")
    node = None
    prefixed = _NODE_PREFIX.match(lhs)
    if prefixed:
        node, lhs = prefixed.group(1), lhs[prefixed.end():]
    if lhs in ("__node", "__name"):
        if not _NODE_NAME.fullmatch(rhs):
            raise bad(f"{rhs!r} is no node name")
        return RemapRule("__node", rhs, node)
    if lhs == "__ns":
        if not _NAMESPACE.fullmatch(rhs):
            raise bad(f"{rhs!r} is no absolute namespace")
        return RemapRule("__ns", rhs, node)
    match = lhs
    for scheme in _SCHEMES:
        if match.startswith(scheme):
            match = match[len(scheme):]
            break
    if "*" in match:
        raise bad("wildcards are not implemented in rcl's remap rules")
    if not _NAME.fullmatch(match):
        raise bad(f"{match!r} is no name to match")
    if not _NAME.fullmatch(rhs):
        raise bad(f"{rhs!r} is no replacement name")
    return RemapRule(lhs, rhs, node)


_PARAM_NAME = re.compile(rf"{_TOKEN}(?:[./]{_TOKEN})*", re.ASCII)
_ENCLAVE = re.compile(r"/(?:[A-Za-z_]\w*(?:/[A-Za-z_]\w*)*)?", re.ASCII)


def _param_rule(rule: str) -> tuple[str | None, str, Any]:
    """`-p [node:]name:=value` as rcl's parser takes it: a plain node name, a parameter name of tokens joined by
    '.' or '/', and a YAML value that is a scalar or a sequence of scalars of one type."""
    import yaml

    def bad(why: str) -> ConfigError:
        return ConfigError(f"--ros-args: cannot parse parameter rule {rule!r}: {why}",
                           hint="valid: -p [NODE:]NAME:=VALUE, NAME of letters, digits, '_', '.' and '/', VALUE a "
                                "YAML scalar or [list] of one type")

    lhs, sep, text = rule.partition(":=")
    if not sep:
        raise bad("no ':='")
    node, colon, name = lhs.rpartition(":")
    if colon and not _NODE_NAME.fullmatch(node):
        raise bad(f"{node!r} is no node name")
    if not _PARAM_NAME.fullmatch(name):
        raise bad(f"{name!r} is no parameter name")
    if text == "":
        raise bad("no value")
    try:
        loaded = _load_yaml(text)
    except yaml.YAMLError as e:
        raise bad(f"the value is no YAML ({str(e).splitlines()[0]})") from None
    if isinstance(loaded, dict):
        raise bad("a mapping is no parameter value")
    if isinstance(loaded, list):
        items = [v for v in loaded if not isinstance(v, list)]
        if any(isinstance(v, dict) for v in items) or len({type(v) for v in items}) > 1:
            raise bad("the items of an array must be of one type")
    return (node if colon else None), name, parse_value(text)


def _parse_argv(ros_argv: list[str]) -> _Parsed:
    out = _Parsed()
    unknown: list[str] = []
    i = 0

    def need(flag: str) -> str:
        if i + 1 >= len(ros_argv):
            raise ConfigError(f"--ros-args: {flag} needs a value")
        return ros_argv[i + 1]

    while i < len(ros_argv):
        a = ros_argv[i]
        if a in ("-r", "--remap"):
            out.rules.append(_remap_rule(need(a)))
            i += 2
        elif a in ("-p", "--param"):
            node, k, v = _param_rule(need(a))
            out.overrides.set(node if node is not None else "/**", k, v)
            i += 2
        elif a == "--params-file":
            f = need(a)
            out.files.append(f)
            out.overrides.add_file(f)  # read here: its keys take their place among the -p rules around it
            i += 2
        elif a == "--log-level":
            out.log_level = need(a)
            if out.log_level.rpartition(":=")[2].upper() not in _SEVERITIES:
                raise ConfigError(f"--ros-args: log level {out.log_level!r} is no severity",
                                  hint="valid: [LOGGER:=]DEBUG, INFO, WARN, ERROR, FATAL or UNSET")
            i += 2
        elif a in ("-e", "--enclave"):
            if not _ENCLAVE.fullmatch(need(a)):
                raise ConfigError(f"--ros-args: enclave {ros_argv[i + 1]!r} is no absolute name",
                                  hint="valid: -e /NAME[/NAME…], names of letters, digits and '_'")
            i += 2
        elif a in ("--log-config-file", "--log-file-name"):
            i += 2
        elif a in _LOGGING_SWITCHES or a == "--ros-args":
            # rcl's logging switches (the client library reads what it needs), and a repeated `--ros-args`
            # (launch_ros's ros_arguments, then its own): rcl just goes on
            i += 1
        else:  # rcl reads on and reports every argument it did not know, once all the rules parsed
            unknown.append(a)
            i += 1
    if unknown:
        raise UnknownRosArgsError(unknown)
    return out


class UnknownRosArgsError(ConfigError):
    """`--ros-args` spans held arguments that are no ROS flag or rule; `unknown` lists them all, in order."""

    def __init__(self, unknown: list[str]) -> None:
        self.unknown = list(unknown)
        listed = ", ".join(repr(a) for a in unknown)
        super().__init__(f"--ros-args: unknown flag{'s' if len(unknown) > 1 else ''} {listed}",
                         hint="valid: -r FROM:=TO, -p NAME:=VALUE, --params-file FILE, --log-level LEVEL")


def check(ros_argv: list[str]) -> None:
    """Raise what `parse` would for these arguments (a malformed rule, an unreadable parameter file, then
    `UnknownRosArgsError`), as rcl does at init for the process's global arguments."""
    _parse_argv(ros_argv)


_SEVERITIES = ("UNSET", "DEBUG", "INFO", "WARN", "ERROR", "FATAL")
_LOGGING_SWITCHES = ("--enable-rosout-logs", "--disable-rosout-logs", "--enable-stdout-logs", "--disable-stdout-logs",
                     "--enable-external-lib-logs", "--disable-external-lib-logs")


def _first(rules: list[RemapRule], match: str, node_name: str | None) -> str | None:
    for r in rules:
        if r.match == match and r.applies_to(node_name):
            return r.replacement
    return None


def parse(
    ros_argv: list[str],
    default_node_name: str | None = None,
    default_namespace: str | None = None,
    *,
    local_argv: list[str] | None = None,
) -> RosArgs:
    """One node's `RosArgs` from the process's (global) `ros_argv` and the node's own `local_argv`.

    `default_node_name` / `default_namespace` are the names the node is created with (`__node:=` and
    `__ns:=` rules prefixed with that name apply to it); parameters are those whose node key matches the
    node's fully qualified name after remapping. Without a default name, only unprefixed rules apply.
    """
    glob = _parse_argv(ros_argv)
    local = _parse_argv(local_argv or [])
    rules = [*local.rules, *glob.rules]  # rcl: local rules are tried first
    node_name = _first(rules, "__node", default_node_name)
    namespace = _first(rules, "__ns", default_node_name)
    name = node_name or default_node_name
    remaps: dict[str, str] = {}
    for r in rules:
        if r.match not in ("__node", "__ns") and r.applies_to(name):
            remaps.setdefault(r.match, r.replacement)
    params: dict[str, Any] = {}
    overrides = ParameterOverrides()
    for layer in (glob.overrides, local.overrides):
        for key, entry in layer.entries.items():
            overrides.entries.setdefault(key, {}).update(entry)
    if name is not None:
        fqn = node_fqn(name, namespace or default_namespace or "/")
        params = {**glob.overrides.for_node(fqn), **local.overrides.for_node(fqn)}
    else:  # no node to match: every `/**` rule and section (a tool reading its own -p)
        for layer in (glob.overrides, local.overrides):
            params.update(layer.entries.get("/**", {}))
    return RosArgs(node_name, namespace, params, remaps, tuple([*glob.files, *local.files]),
                   local.log_level or glob.log_level, tuple(rules), overrides)


def current(default_node_name: str | None = None, default_namespace: str | None = None) -> RosArgs:
    """The `--ros-args` this process was started with, parsed for the node `default_node_name` creates."""
    return parse(_current, default_node_name, default_namespace)


def build(
    *,
    node_name: str | None = None,
    namespace: str | None = None,
    params_files: list[str] | None = None,
    params: dict[str, Any] | None = None,
    remaps: dict[str, str] | None = None,
) -> list[str]:
    """The `--ros-args …` tail for a command line (empty when there is nothing to pass)."""
    out: list[str] = []
    if node_name:
        out += ["-r", f"__node:={node_name}"]
    if namespace and namespace != "/":
        out += ["-r", f"__ns:={namespace}"]
    for f in params_files or []:
        out += ["--params-file", str(f)]
    import yaml

    for k, v in (params or {}).items():
        out += ["-p", f"{k}:={v if isinstance(v, str) else yaml.safe_dump(v, default_flow_style=True).strip()}"]
    for k, v in (remaps or {}).items():
        out += ["-r", f"{k}:={v}"]
    return ["--ros-args", *out] if out else []
