"""Parameter declaration tables: one `ParamDecl` per entry of a ros2_controllers `*_parameters.yaml`.

generate_parameter_library turns such a YAML (type, default_value, description, read_only, validation) into
both the node's declarations and the checks applied to every value; a table of `ParamDecl` does the same
here, in one place:
  - `read_declared(table, params, controller)` validates the node's values (file overrides, or the defaults)
    into a dict of typed values, raising ParameterError naming `<controller>.<parameter>`;
  - `declare_all(node, table, controller)` declares every entry on the controller's node with a
    ParameterDescriptor built from the same entry (read_only, ranges, the validation as text), so
    `param describe/get/set` see exactly what the controller validates against.
Validators have generate_parameter_library's names (`gt<>`, `gt_eq<>`, `lt<>`, `lt_eq<>`, `bounds<>`,
`not_empty<>`, `unique<>`, `size_eq<>`, `one_of<>`, `lower_element_bounds<>`). A double accepts an integer
(rclcpp would refuse `wheel_radius: 1`; nobody means anything else by it).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from diffctl.errors import ParameterError, suggest

# generate_parameter_library type name → rcl_interfaces ParameterType name (ParameterDescriptor.type).
_ROS_TYPE = {
    "bool": "bool",
    "int": "integer",
    "double": "double",
    "string": "string",
    "bool_array": "bool_array",
    "int_array": "integer_array",
    "double_array": "double_array",
    "string_array": "string_array",
}
# Keys the controller manager owns on every controller node (`<name>.type`, `.params_file`, …): never unknown.
MANAGER_KEYS = frozenset(
    {"type", "update_rate", "use_sim_time", "params_file", "is_async", "thread_priority", "fallback_controllers"}
)
# Declared by rclcpp on every node (node_parameters.cpp, node.cpp, the QoS overriding options): a file that
# sets them for a controller is not setting an unknown controller parameter.
NODE_KEYS = frozenset({"use_sim_time", "start_type_description_service"})
NODE_KEY_PREFIXES = ("qos_overrides.",)
_DOUBLE_MAX = sys.float_info.max
_INT_MAX = 2**63 - 1


@dataclass(frozen=True)
class Check:
    """One validator of generate_parameter_library, e.g. Check("gt", (0.0,)) for `gt<>: [0.0]`."""

    kind: str
    args: tuple[Any, ...] = ()

    @property
    def text(self) -> str:
        return f"{self.kind}<>: {list(self.args)}"

    def reason(self, value: Any) -> str | None:
        """Why `value` fails this check, or None when it passes."""
        k, a = self.kind, self.args
        if k in _COMPARE:
            if isinstance(value, list):  # element-wise on arrays, as the library's *_element_* forms
                return next((r for r in (self.reason(v) for v in value) if r), None)
            op, test = _COMPARE[k]
            if test(value, a):
                return None
            return f"{value!r} must be {op(a)}"
        if k == "lower_element_bounds":
            bad = [v for v in value if not v >= a[0]]
            return f"{value!r} contains {bad[0]!r}: every entry must be ≥ {a[0]!r}" if bad else None
        if k == "not_empty":
            return f"{value!r} must not be empty" if len(value) == 0 else None
        if k == "unique":
            dups = sorted({str(v) for v in value if value.count(v) > 1})
            return f"{value!r} names {dups[0]!r} more than once" if dups else None
        if k == "size_eq":
            return f"{value!r} has {len(value)} entries, expected {a[0]}" if len(value) != a[0] else None
        if k == "one_of":
            return f"{value!r} is not one of {list(a[0])}" if value not in a[0] else None
        raise ValueError(f"unknown validator {k!r}")


_COMPARE: dict[str, tuple[Any, Any]] = {
    "gt": (lambda a: f"> {a[0]!r}", lambda v, a: v > a[0]),
    "gt_eq": (lambda a: f"≥ {a[0]!r}", lambda v, a: v >= a[0]),
    "lt": (lambda a: f"< {a[0]!r}", lambda v, a: v < a[0]),
    "lt_eq": (lambda a: f"≤ {a[0]!r}", lambda v, a: v <= a[0]),
    "bounds": (lambda a: f"within [{a[0]!r}, {a[1]!r}]", lambda v, a: a[0] <= v <= a[1]),
}


@dataclass(frozen=True)
class ParamDecl:
    """One parameter as its `*_parameters.yaml` declares it."""

    name: str
    type: str  # generate_parameter_library's: bool, int, double, string, *_array
    default: Any
    description: str = ""
    read_only: bool = False
    checks: tuple[Check, ...] = ()

    @property
    def ros_type(self) -> str:
        return _ROS_TYPE[self.type]

    def descriptor(self) -> Any:
        """The ParameterDescriptor a node announces for this parameter."""
        from diffctl.bus.parameters import ParameterDescriptor

        fp: tuple[float, float, float] | None = None
        ir: tuple[int, int, int] | None = None
        # A NaN default means "unset" and a ROS range would refuse it, so such parameters announce no range.
        ranged = not (self.type == "double" and self.default != self.default)
        for c in self.checks if ranged else ():
            lo, hi = _range_of(c, integer=self.type == "int")
            if lo is None:
                continue
            if self.type == "double":
                fp = (float(lo), float(hi), 0.0)
            elif self.type == "int":
                ir = (int(lo), int(hi), 0)
        return ParameterDescriptor(
            type=self.ros_type,
            description=self.description,
            read_only=self.read_only,
            floating_point_range=fp,
            integer_range=ir,
            additional_constraints="; ".join(c.text for c in self.checks),
        )


def _range_of(c: Check, *, integer: bool) -> tuple[float | None, float | None]:
    """The descriptor range a check implies (ranges are inclusive, so only the inclusive checks give one)."""
    top, bottom = (_INT_MAX, -_INT_MAX - 1) if integer else (_DOUBLE_MAX, -_DOUBLE_MAX)
    if c.kind == "bounds":
        return c.args[0], c.args[1]
    if c.kind == "gt_eq":
        return c.args[0], top
    if c.kind == "lt_eq":
        return bottom, c.args[0]
    return None, None


def _is_number(v: Any) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool)


def coerce(decl: ParamDecl, raw: Any) -> Any:
    """`raw` as a value of the declared type, or raise ValueError saying what was expected."""
    t = decl.type
    if t == "bool":
        if isinstance(raw, bool):
            return raw
        raise ValueError(f"{raw!r} is not a bool (write true or false)")
    if t == "int":
        if isinstance(raw, float) and math.isfinite(raw) and raw.is_integer():
            return int(raw)
        if isinstance(raw, int) and not isinstance(raw, bool):
            return raw
        raise ValueError(f"{raw!r} is not an integer")
    if t == "double":
        if _is_number(raw):
            return float(raw)
        raise ValueError(f"{raw!r} is not a number (write .nan for 'not set' where allowed)")
    if t == "string":
        if isinstance(raw, str):
            return raw
        raise ValueError(f"{raw!r} is not a string")
    if not isinstance(raw, list | tuple):
        raise ValueError(f"{raw!r} is not a list ({decl.type})")
    items = list(raw)
    element = ParamDecl(decl.name, t.removesuffix("_array"), None)
    try:
        return [coerce(element, v) for v in items]
    except ValueError as e:
        raise ValueError(f"{items!r} is not a {t}: {e}") from None


def check(decl: ParamDecl, raw: Any, controller: str) -> Any:
    """The typed, validated value of `decl` (raises ParameterError naming `<controller>.<name>`)."""
    try:
        value = coerce(decl, raw)
    except ValueError as e:
        raise ParameterError(str(e), field=f"{controller}.{decl.name}", hint=_valid_text(decl)) from None
    unset = decl.type == "double" and value != value and decl.default != decl.default  # NaN: "no value"
    if decl.type == "double" and decl.checks and not unset and not math.isfinite(value):
        raise ParameterError(
            f"{raw!r} is not a finite number", field=f"{controller}.{decl.name}", hint=_valid_text(decl)
        )
    for c in () if unset else decl.checks:
        why = c.reason(value)
        if why is not None:
            if why.startswith(repr(value)):  # quote the value as the user wrote it (1, not 1.0)
                why = repr(raw) + why[len(repr(value)) :]
            raise ParameterError(why, field=f"{controller}.{decl.name}", hint=_valid_text(decl))
    return value


def _valid_text(decl: ParamDecl) -> str:
    rules = ", ".join(c.text for c in decl.checks)
    return f"{decl.type}{', ' + rules if rules else ''}; default {decl.default!r}"


def table(decls: Iterable[ParamDecl]) -> dict[str, ParamDecl]:
    return {d.name: d for d in decls}


def read_declared(decls: Mapping[str, ParamDecl], params: Mapping[str, Any], controller: str) -> dict[str, Any]:
    """Every declared parameter's typed value: the one in `params` if given, else the default."""
    return {name: check(d, params.get(name, d.default), controller) for name, d in decls.items()}


def unknown_key_warnings(
    decls: Mapping[str, ParamDecl], params: Mapping[str, Any], controller: str, also_known: Iterable[str] = ()
) -> list[str]:
    """One warning per key in `params` the table does not declare (and the manager does not own)."""
    known = set(decls) | MANAGER_KEYS | NODE_KEYS | set(also_known)
    return [
        f"unknown parameter '{controller}.{k}' is ignored{suggest(k, sorted(known))}"
        for k in params
        if k not in known and not k.startswith(NODE_KEY_PREFIXES)
    ]


def declare_all(node: Any, decls: Mapping[str, ParamDecl], controller: str) -> dict[str, Any]:
    """Validate the node's values against `decls`, then declare each on the node with its descriptor.

    Returns the typed values. A node without the parameter API (a test double) is only validated.
    """
    values = read_declared(decls, node.params, controller)
    declare = getattr(node, "declare_parameter", None)
    if declare is None:
        return values
    overrides = getattr(getattr(node, "parameters", None), "overrides", {})
    for name, d in decls.items():
        if name in overrides:
            overrides[name] = values[name]  # the typed override: 10.0 given for an integer is 10
        values[name] = declare(name, values[name], d.descriptor())
    return values


# Declared by controller_interface on every controller node (controller_interface_base.cpp).
BASE_DECLS: tuple[ParamDecl, ...] = (
    ParamDecl(
        "update_rate",
        "int",
        0,
        "Rate of the controller's update() in Hz; 0 = the manager's rate.",
        read_only=True,
        checks=(Check("gt_eq", (0,)),),
    ),
    ParamDecl("is_async", "bool", False, "Whether the controller runs asynchronously.", read_only=True),
    ParamDecl(
        "thread_priority",
        "int",
        50,
        "Priority of an async controller's thread.",
        read_only=True,
        checks=(Check("bounds", (0, 99)),),
    ),
)
