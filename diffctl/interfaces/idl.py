""".msg, .srv and .action text → type definitions, as rosidl_adapter reads them (ROS 2 Jazzy).

A definition is rosbags' form — `(constants, fields)` with field descriptors `(Nodetype, spec)` — so the
bus's typestore, its RIHS01 hashing and its CDR compiler take it as is; what rosbags drops (field defaults)
is kept beside it. Like rosidl, a .msg `char` is uint8 and `byte` is an octet; unqualified type names are
of the same package. Errors name the file, line and field, with what would be valid.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any

from rosbags.typesys.base import Nodetype

from diffctl.errors import ConfigError, suggest

PRIMITIVES = ("bool", "byte", "char", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64",
              "float32", "float64", "string", "wstring")
_INT_BITS = {"int8": 8, "uint8": 8, "int16": 16, "uint16": 16, "int32": 32, "uint32": 32, "int64": 64,
             "uint64": 64, "byte": 8}
EMPTY_MEMBER = "structure_needs_at_least_one_member"
_FIELD_NAME = re.compile(r"^[a-z][a-z0-9_]*$")
_CONST_NAME = re.compile(r"^[A-Z][A-Z0-9_]*$")
_TYPE = re.compile(r"^(?P<base>[A-Za-z][A-Za-z0-9_/]*)(?:<=(?P<sbound>\d+))?(?P<arr>\[(?P<abound><=)?(?P<n>\d*)\])?$")


class InterfaceError(ConfigError, ImportError):
    """A malformed interface definition (file, line, what is wrong and what would be valid); an ImportError
    too, since it surfaces from the import of the package."""


@dataclass
class TypeDef:
    """One message type: rosbags' (constants, fields) plus the .msg defaults rosbags does not keep."""

    name: str  # pkg/msg/Name, pkg/srv/Name_Request, pkg/action/Name_Goal, …
    constants: list[tuple[str, str, Any]] = field(default_factory=list)
    fields: list[tuple[str, tuple]] = field(default_factory=list)
    defaults: dict[str, Any] = field(default_factory=dict)
    lines: dict[str, int] = field(default_factory=dict)  # field → its line in the source text (errors)

    def rosbags(self) -> tuple[list, list]:
        return (self.constants, self.fields)


def _strip_comment(line: str) -> str:
    # rosidl_adapter cuts at the first '#', inside quotes too (a '#' cannot be part of a value)
    return line.split("#", 1)[0]


def _base_desc(base: str, sbound: str | None, pkg: str, where: dict[str, Any]) -> tuple:
    if base in PRIMITIVES:
        if sbound is not None and base not in ("string", "wstring"):
            raise InterfaceError(f"only strings take an upper bound, not {base!r}", **where)
        if sbound is not None and int(sbound) == 0:
            raise InterfaceError(f"invalid type '{base}<={sbound}': the upper bound must be > 0", **where)
        # rosidl reads a .msg `char` as uint8 (rosidl_adapter); the RIHS01 hash depends on it.
        return (Nodetype.BASE, ("uint8" if base == "char" else base, int(sbound or 0)))
    if sbound is not None:
        raise InterfaceError(f"only strings take an upper bound, not {base!r}", **where)
    parts = base.split("/")
    if len(parts) == 1:
        parts = [pkg, parts[0]]
    if len(parts) == 3 and all(parts):
        # rosidl_adapter takes a message type of another package as package/Name only
        raise InterfaceError(f"invalid type {base!r}: in a .msg another package's type is package/Name",
                             **where, hint=f"{parts[0]}/{parts[2]}")
    if len(parts) == 2:
        parts = [parts[0], "msg", parts[1]]
    if len(parts) != 3 or not all(parts) or not parts[2][:1].isupper():
        raise InterfaceError(
            f"invalid type {base!r}: a primitive ({', '.join(PRIMITIVES)}) or a message type "
            "Name / package/Name", **where)
    return (Nodetype.NAME, "/".join(parts))


def parse_type(text: str, pkg: str, where: dict[str, Any]) -> tuple:
    """A .msg field type (`float64[3]`, `string<=10[<=5]`, `geometry_msgs/Point[]`) as a rosbags descriptor."""
    m = _TYPE.match(text)
    if not m:
        raise InterfaceError(f"invalid field type {text!r}", **where,
                             hint="e.g. float64, string<=10, int32[4], geometry_msgs/Point[], uint8[<=16]")
    desc = _base_desc(m["base"], m["sbound"], pkg, where)
    if m["arr"] is None:
        return desc
    if m["abound"]:
        if not m["n"] or int(m["n"]) == 0:
            raise InterfaceError(f"invalid bounded sequence {text!r}: the bound must be > 0", **where)
        return (Nodetype.SEQUENCE, (desc, int(m["n"])))
    if m["n"]:
        if int(m["n"]) == 0:
            raise InterfaceError(f"invalid array {text!r}: the size must be > 0", **where)
        return (Nodetype.ARRAY, (desc, int(m["n"])))
    return (Nodetype.SEQUENCE, (desc, 0))


def _unquote(text: str, where: dict[str, Any]) -> str:
    """rosidl_adapter's string values: outer quotes removed, an unescaped inner quote of that kind refused and
    the escaped ones unescaped."""
    for quote in "\"'":
        if len(text) >= 2 and text.startswith(quote) and text.endswith(quote):
            inner = text[1:-1]
            if re.search(r"(?<!\\)" + quote, inner):
                raise InterfaceError(f"string value {text}: an inner {quote} must be escaped as \\{quote}", **where)
            return inner.replace("\\" + quote, quote)
    return text


def parse_primitive(base: str, bound: int, text: str, where: dict[str, Any]) -> Any:
    """A default or constant value as rosidl reads it: bools from true/false/1/0, range-checked integers."""
    text = text.strip()
    if base == "bool":
        low = text.lower()
        if low in ("true", "1"):
            return True
        if low in ("false", "0"):
            return False
        raise InterfaceError(f"invalid bool value {text!r}", **where, hint="true, false, 1 or 0")
    if base in _INT_BITS:
        try:
            value = int(text, 0) if text.lower().startswith(("0x", "0o", "0b")) else int(text)
        except ValueError:
            raise InterfaceError(f"invalid {base} value {text!r}", **where) from None
        bits = _INT_BITS[base]
        lo, hi = (0, 2**bits - 1) if base.startswith("u") or base == "byte" else (-(2 ** (bits - 1)),
                                                                                    2 ** (bits - 1) - 1)
        if not lo <= value <= hi:
            raise InterfaceError(f"{base} value {value} out of range [{lo}, {hi}]", **where)
        return value
    if base in ("float32", "float64"):
        try:
            return float(text)
        except ValueError:
            raise InterfaceError(f"invalid {base} value {text!r}", **where) from None
    value = _unquote(text, where)
    if bound and len(value) > bound:
        raise InterfaceError(f"string value {value!r} longer than its bound {bound}", **where)
    return value


def _split_list(text: str) -> list[str]:
    items, cur, quote = [], "", None
    for ch in text:
        if quote:
            cur += ch
            if ch == quote:
                quote = None
        elif ch in "\"'":
            quote = ch
            cur += ch
        elif ch == ",":
            items.append(cur)
            cur = ""
        else:
            cur += ch
    if cur.strip() or items:
        items.append(cur)
    return [i.strip() for i in items]


def _split_strings(text: str, where: dict[str, Any]) -> list[str]:
    """A string array's elements as rosidl_adapter walks them: a quoted element runs to the next quote of
    its kind that no backslash escapes (escaped ones of that kind unescaped, commas kept), an unquoted one
    to the next comma; a trailing comma adds nothing, an empty element is an error."""
    items: list[str] = []
    rest = text.lstrip(" ")
    while rest:
        if rest[0] == ",":
            raise InterfaceError(f"unexpected ',' at {rest!r} in the string array default", **where,
                                 hint='e.g. ["a", "b,c", \'d\']')
        quote = rest[0] if rest[0] in "\"'" else None
        if quote:
            end = next((i for i in range(1, len(rest)) if rest[i] == quote and rest[i - 1] != "\\"), -1)
            if end < 0:
                raise InterfaceError(f"string {rest!r} has no closing {quote}", **where)
            items.append(rest[1:end].replace("\\" + quote, quote))
            rest = rest[end + 1:]
        else:
            comma = rest.find(",")
            items.append(rest if comma < 0 else rest[:comma])
            rest = "" if comma < 0 else rest[comma:]
        rest = rest.lstrip(" ")
        if rest.startswith(","):
            rest = rest[1:].lstrip(" ")
    return items


def parse_default(desc: tuple, text: str, where: dict[str, Any]) -> Any:
    kind, spec = desc
    if kind == Nodetype.BASE:
        return parse_primitive(spec[0], spec[1], text, where)
    if kind == Nodetype.NAME:
        raise InterfaceError("message fields take no default value", **where)
    sub, n = spec
    if sub[0] != Nodetype.BASE:
        raise InterfaceError("arrays of messages take no default value", **where)
    t = text.strip()
    if not (t.startswith("[") and t.endswith("]")):
        raise InterfaceError(f"invalid array default {text!r}", **where, hint="e.g. [1, 2, 3]")
    strings = sub[1][0] in ("string", "wstring")
    elements = _split_strings(t[1:-1], where) if strings else _split_list(t[1:-1])
    values = [parse_primitive(sub[1][0], sub[1][1], v, where) for v in elements]
    if kind == Nodetype.ARRAY and len(values) != n:
        raise InterfaceError(f"the default has {len(values)} values, the array {n}", **where)
    if kind == Nodetype.SEQUENCE and n and len(values) > n:
        raise InterfaceError(f"the default has {len(values)} values, more than the bound {n}", **where)
    return values


def parse_message(text: str, typename: str, source: str | None = None, first_line: int = 1) -> TypeDef:
    """One .msg text (or one section of a .srv/.action) as the definition of `typename`."""
    pkg = typename.split("/")[0]
    td = TypeDef(typename)
    names: set[str] = set()
    for offset, raw in enumerate(text.splitlines()):
        where: dict[str, Any] = {"source": source, "line": first_line + offset}
        line = _strip_comment(raw.replace("\t", " ")).strip()
        if not line:
            continue
        type_text, _, rest = line.partition(" ")
        rest = rest.strip()
        if not rest:
            raise InterfaceError(f"{line!r} is not 'type name', 'type name default' or 'type NAME=value'",
                                 **where)
        desc = parse_type(type_text, pkg, where)
        if "=" in rest:  # rosidl_adapter: any '=' makes the line a constant
            name, _, value = rest.partition("=")
            name = name.strip()
            where["field"] = name
            if desc[0] != Nodetype.BASE:
                raise InterfaceError("constants must be of a primitive or string type", **where)
            if not _CONST_NAME.match(name) or "__" in name or name.endswith("_"):
                raise InterfaceError(
                    f"invalid constant name {name!r}", **where,
                    hint="upper case letters, digits and single '_', starting with a letter, not ending with '_'")
            if name in names:
                raise InterfaceError(f"duplicate name {name!r}", **where)
            names.add(name)
            base = desc[1][0]
            td.constants.append((name, base, parse_primitive(base, desc[1][1], value.strip(), where)))
            continue
        name, _, default = rest.partition(" ")
        where["field"] = name
        if not _FIELD_NAME.match(name) or "__" in name or name.endswith("_"):
            raise InterfaceError(
                f"invalid field name {name!r}", **where,
                hint="lower case letters, digits and single '_', starting with a letter, not ending with '_'")
        if name in names:
            raise InterfaceError(f"duplicate field {name!r}", **where)
        names.add(name)
        td.fields.append((name, desc))
        td.lines[name] = where["line"]
        if default.strip():
            td.defaults[name] = parse_default(desc, default, where)
    if not td.fields:
        # IDL structures need a member: rosidl adds this byte (on the wire and in the type hash).
        td.fields.append((EMPTY_MEMBER, (Nodetype.BASE, ("uint8", 0))))
    return td


def _sections(text: str, count: int, what: str, source: str | None) -> list[tuple[str, int]]:
    out: list[tuple[str, int]] = []
    start, buf = 1, []
    for i, line in enumerate(text.splitlines(), 1):
        if line == "---":  # rosidl_adapter takes only this exact line as the separator
            out.append(("\n".join(buf), start))
            buf, start = [], i + 1
        else:
            buf.append(line)
    out.append(("\n".join(buf), start))
    if len(out) != count:
        raise InterfaceError(f"a {what} has {count} sections separated by '---', this one has {len(out)}",
                             source=source)
    return out


def service_defs(name: str, text: str, source: str | None = None) -> list[TypeDef]:
    """`pkg/srv/Name` text → its Request and Response definitions (the Event and wrapper: `wrappers`)."""
    (req, l1), (resp, l2) = _sections(text, 2, ".srv", source)
    return [parse_message(req, f"{name}_Request", source, l1), parse_message(resp, f"{name}_Response", source, l2)]


def action_defs(name: str, text: str, source: str | None = None) -> list[TypeDef]:
    """`pkg/action/Name` text → its Goal, Result and Feedback definitions."""
    (goal, l1), (result, l2), (feedback, l3) = _sections(text, 3, ".action", source)
    return [parse_message(goal, f"{name}_Goal", source, l1), parse_message(result, f"{name}_Result", source, l2),
            parse_message(feedback, f"{name}_Feedback", source, l3)]


def _n(t: str) -> tuple:
    return (Nodetype.NAME, t)


def _opt(t: str) -> tuple:
    return (Nodetype.SEQUENCE, ((Nodetype.NAME, t), 1))


def service_wrappers(name: str) -> list[TypeDef]:
    """The Event message and the service's own type (whose RIHS01 is the service's), as rosidl defines them."""
    return [
        TypeDef(f"{name}_Event", [], [("info", _n("service_msgs/msg/ServiceEventInfo")),
                                      ("request", _opt(f"{name}_Request")), ("response", _opt(f"{name}_Response"))]),
        TypeDef(name, [], [("request_message", _n(f"{name}_Request")), ("response_message", _n(f"{name}_Response")),
                           ("event_message", _n(f"{name}_Event"))]),
    ]


def action_wrappers(name: str) -> list[TypeDef]:
    """SendGoal and GetResult services, the FeedbackMessage and the action's own type (rosidl's Action)."""
    uuid = _n("unique_identifier_msgs/msg/UUID")
    send, get = f"{name}_SendGoal", f"{name}_GetResult"
    return [
        TypeDef(f"{send}_Request", [], [("goal_id", uuid), ("goal", _n(f"{name}_Goal"))]),
        TypeDef(f"{send}_Response", [], [("accepted", (Nodetype.BASE, ("bool", 0))),
                                         ("stamp", _n("builtin_interfaces/msg/Time"))]),
        *service_wrappers(send),
        TypeDef(f"{get}_Request", [], [("goal_id", uuid)]),
        TypeDef(f"{get}_Response", [], [("status", (Nodetype.BASE, ("int8", 0))), ("result", _n(f"{name}_Result"))]),
        *service_wrappers(get),
        TypeDef(f"{name}_FeedbackMessage", [], [("goal_id", uuid), ("feedback", _n(f"{name}_Feedback"))]),
        TypeDef(name, [], [("goal", _n(f"{name}_Goal")), ("result", _n(f"{name}_Result")),
                           ("feedback", _n(f"{name}_Feedback")), ("send_goal_service", _n(send)),
                           ("get_result_service", _n(get)), ("feedback_message", _n(f"{name}_FeedbackMessage"))]),
    ]


def interface_defs(name: str, text: str, source: str | None = None) -> list[TypeDef]:
    """Every type one interface file (.msg/.srv/.action, or .idl) defines: a message; a service's four; an
    action's sixteen."""
    kind = name.split("/")[1]
    if source is not None and source.endswith(".idl") and kind in ("msg", "srv", "action"):
        from diffctl.interfaces.idl_files import idl_defs

        wrappers = service_wrappers(name) if kind == "srv" else action_wrappers(name) if kind == "action" else []
        return [*idl_defs(name, text, source), *wrappers]
    if kind == "msg":
        return [parse_message(text, name, source)]
    if kind == "srv":
        return [*service_defs(name, text, source), *service_wrappers(name)]
    if kind == "action":
        return [*action_defs(name, text, source), *action_wrappers(name)]
    raise InterfaceError(f"unknown interface kind {kind!r}{suggest(kind, ['msg', 'srv', 'action'])}", source=source)
