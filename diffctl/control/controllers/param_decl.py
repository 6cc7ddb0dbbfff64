"""Parameter declaration tables: one `ParamDecl` per entry of a ros2_controllers `*_parameters.yaml`.

generate_parameter_library turns such a YAML (type, default_value, description, read_only, validation,
additional_constraints) into both the node's declarations and the checks applied to every value; a table of
`ParamDecl` does the same here, in one place:
  - `read_declared(table, params, controller)` validates values (the node's overrides, or the defaults) into a
    dict of typed values, raising ParameterError naming `<controller>.<parameter>`;
  - `declare_all(node, table, controller)` validates the node's overrides, then declares every entry on the
    controller's client Node with the ParameterDescriptor the library would give it: the description, read_only,
    additional_constraints as written, and the range its validators imply (`bounds<>`, `gt_eq<>`/`lt_eq<>`,
    `gt<>`/`lt<>` just past the limit) on doubles and integers; the node then enforces the range itself;
  - `validate_changes(node, table, controller)` refuses a `param set` that breaks a rule, as the library's
    parameter listener does.
Validators have generate_parameter_library's names (`gt<>`, `gt_eq<>`, `lt<>`, `lt_eq<>`, `bounds<>`,
`not_empty<>`, `unique<>`, `size_eq<>`, `one_of<>`, `lower_element_bounds<>`) and control_toolbox's
`control_filters::gt_eq_or_nan<>` / `lt_eq_or_nan<>`. A double accepts an integer (rclcpp would refuse
`wheel_radius: 1`; nobody means anything else by it).
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
# Keys the controller manager owns on every controller node (`<name>.type`, `.params_file`, …) and the ones
# controller_interface declares on it: never unknown.
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

    @property
    def base_name(self) -> str:
        return self.kind.rpartition("::")[2]

    def reason(self, value: Any) -> str | None:
        """Why `value` fails this check, or None when it passes."""
        k, a = self.kind, self.args
        if k in _OR_NAN:
            if isinstance(value, list):
                return next((r for r in (self.reason(v) for v in value) if r), None)
            if value != value:  # NaN: "not set", always allowed
                return None
            return Check(_OR_NAN[k], a).reason(value)
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


_OR_NAN = {"control_filters::gt_eq_or_nan": "gt_eq", "control_filters::lt_eq_or_nan": "lt_eq"}


@dataclass(frozen=True)
class ParamDecl:
    """One parameter as its `*_parameters.yaml` declares it."""

    name: str
    type: str  # generate_parameter_library's: bool, int, double, string, *_array
    default: Any
    description: str = ""
    read_only: bool = False
    checks: tuple[Check, ...] = ()  # the YAML's validation (they shape the descriptor)
    additional_constraints: str = ""
    also: tuple[Check, ...] = ()  # diffctl's checks beyond the YAML's (not announced)

    @property
    def ros_type(self) -> str:
        return _ROS_TYPE[self.type]

    def descriptor(self) -> Any:
        """The ParameterDescriptor generate_parameter_library declares this parameter with."""
        from diffctl.client.interfaces import cls

        d = cls("rcl_interfaces/msg/ParameterDescriptor")(
            description=self.description, read_only=self.read_only, additional_constraints=self.additional_constraints
        )
        lo, hi = self.range()
        if lo is None and hi is None:
            return d
        if self.type.startswith("double"):
            d.floating_point_range = [cls("rcl_interfaces/msg/FloatingPointRange")(
                from_value=-_DOUBLE_MAX if lo is None else float(lo),
                to_value=_DOUBLE_MAX if hi is None else float(hi), step=0.0)]
        elif self.type.startswith("int"):
            d.integer_range = [cls("rcl_interfaces/msg/IntegerRange")(
                from_value=-_INT_MAX - 1 if lo is None else int(lo), to_value=_INT_MAX if hi is None else int(hi),
                step=0)]
        return d

    def range(self) -> tuple[float | None, float | None]:
        """The range the validators imply, as the library computes it (the last validator giving a bound wins;
        an exclusive limit becomes the next representable value inside it)."""
        lo: float | None = None
        hi: float | None = None
        integer = self.type.startswith("int")
        for c in self.checks:
            name, base = c.kind, c.base_name
            if not ("bounds" in name or "lt" in name or "gt" in name):
                continue
            if len(c.args) == 2:
                lo, hi = c.args
            elif len(c.args) != 1:
                continue
            elif "lower" in name or base == "gt_eq":
                lo = c.args[0]
            elif base == "gt":
                lo = c.args[0] + 1 if integer else math.nextafter(c.args[0], math.inf)
            elif "upper" in name or base == "lt_eq":
                hi = c.args[0]
            elif base == "lt":
                hi = c.args[0] - 1 if integer else math.nextafter(c.args[0], -math.inf)
        return lo, hi


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
    checks = decl.checks + decl.also
    if decl.type == "double" and checks and not unset and not math.isfinite(value):
        raise ParameterError(
            f"{raw!r} is not a finite number", field=f"{controller}.{decl.name}", hint=_valid_text(decl)
        )
    for c in () if unset else checks:
        why = c.reason(value)
        if why is not None:
            if why.startswith(repr(value)):  # quote the value as the user wrote it (1, not 1.0)
                why = repr(raw) + why[len(repr(value)) :]
            raise ParameterError(why, field=f"{controller}.{decl.name}", hint=_valid_text(decl))
    return value


def _valid_text(decl: ParamDecl) -> str:
    rules = ", ".join(c.text for c in decl.checks + decl.also)
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


def overrides(node: Any) -> dict[str, Any]:
    """The values a node was started with (its parameter files and -p rules, for its name), by parameter name
    (rclcpp's NodeParametersInterface::get_parameter_overrides)."""
    return {name: p.value for name, p in node.get_parameter_overrides().items()}


def declare_all(node: Any, decls: Mapping[str, ParamDecl], controller: str) -> dict[str, Any]:
    """Validate the node's overrides against `decls`, then declare each parameter on the node with its
    descriptor and the validated value. Returns the typed values (raises ParameterError)."""
    values = read_declared(decls, overrides(node), controller)
    batch = []
    for name, d in decls.items():
        if node.has_parameter(name):
            values[name] = node.get_parameter(name).value
        elif d.type.endswith("_array") and len(values[name]) == 0:
            declare(node, d, values[name])
        else:
            batch.append((name, values[name], d.descriptor()))
    node.declare_parameters("", batch, ignore_override=True)  # one call for the lot, as the library declares
    return values


def declare(node: Any, decl: ParamDecl, value: Any) -> None:
    """Declare one parameter with its descriptor and `value` (not the node's override: it was validated).
    An empty array is declared by its type, set, then given its descriptor: rclpy types a value by its contents
    and would take `[]` for a byte array."""
    if not (decl.type.endswith("_array") and len(value) == 0):
        node.declare_parameter(decl.name, value, decl.descriptor(), ignore_override=True)
        return
    from diffctl.client.parameter import Parameter

    kind = Parameter.Type[decl.ros_type.upper()]
    descriptor = decl.descriptor()
    writable = decl.descriptor()
    writable.read_only = False
    node.declare_parameter(decl.name, kind, writable, ignore_override=True)
    node.set_parameters([Parameter(decl.name, kind, [])])
    if descriptor.read_only:
        descriptor.type = kind.value
        node.set_descriptor(decl.name, descriptor)


def set_result(reason: str | None) -> Any:
    """rcl_interfaces/SetParametersResult: successful unless `reason`."""
    from diffctl.client.interfaces import cls

    return cls("rcl_interfaces/msg/SetParametersResult")(successful=reason is None, reason=reason or "")


def current_values(node: Any, decls: Mapping[str, ParamDecl]) -> dict[str, Any]:
    """The node's present values of the declared parameters."""
    return {name: node.get_parameter(name).value for name in decls if node.has_parameter(name)}


def changed_values(node: Any, decls: Mapping[str, ParamDecl], parameters: Iterable[Any]) -> dict[str, Any]:
    """The node's values with `parameters` (a set request) applied, limited to the table's names."""
    values = current_values(node, decls)
    values.update({p.name: p.value for p in parameters if p.name in decls})
    return values
