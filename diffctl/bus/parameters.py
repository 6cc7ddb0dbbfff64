"""A node's parameters as rclcpp keeps them: declared with descriptors, validated, changed atomically.

Pure bookkeeping, no I/O: `ParameterStore` decides what a declare/set does and reports each accepted change
to a listener (the node turns that into `/parameter_events`). Rules follow rclcpp's `NodeParameters`:
a statically typed parameter refuses a value of another type, read-only parameters are fixed once declared,
ranges are inclusive with an optional step, set-callbacks can refuse a whole set, and parameters given as
overrides but never declared stay readable and settable (`allow_undeclared_parameters`, as the
controller_manager and the controllers run in ROS).
"""

from __future__ import annotations

import math
import threading
from collections.abc import Callable, Iterable
from dataclasses import dataclass, replace
from typing import Any

from diffctl.errors import ConfigError

# rcl_interfaces/msg/ParameterType
TYPE_CODES: dict[str, int] = {
    "not_set": 0, "bool": 1, "integer": 2, "double": 3, "string": 4, "byte_array": 5,
    "bool_array": 6, "integer_array": 7, "double_array": 8, "string_array": 9,
}
TYPE_NAMES: dict[int, str] = {v: k for k, v in TYPE_CODES.items()}
_ROS_TYPE_WORD = {
    "not_set": "not set", "bool": "bool", "integer": "integer", "double": "double", "string": "string",
    "byte_array": "byte_array", "bool_array": "bool_array", "integer_array": "integer_array",
    "double_array": "double_array", "string_array": "string_array",
}


@dataclass(frozen=True)
class ParameterDescriptor:
    """rcl_interfaces/msg/ParameterDescriptor without the name; `type` None means "the default's type"."""

    type: str | None = None
    description: str = ""
    read_only: bool = False
    floating_point_range: tuple[float, float, float] | None = None  # (from, to, step)
    integer_range: tuple[int, int, int] | None = None
    additional_constraints: str = ""
    dynamic_typing: bool = False

    def __post_init__(self) -> None:
        if self.type is not None and self.type not in TYPE_CODES:
            raise ConfigError(f"parameter descriptor: unknown type {self.type!r}",
                              hint="one of " + ", ".join(TYPE_CODES))
        if self.floating_point_range is not None and self.integer_range is not None:
            raise ConfigError("parameter descriptor: floating_point_range and integer_range are mutually exclusive")
        for rng, what in ((self.floating_point_range, "floating_point_range"), (self.integer_range, "integer_range")):
            if rng is None:
                continue
            if len(rng) != 3:
                raise ConfigError(f"parameter descriptor: {what} must be (from, to, step)")
            lo, hi, step = rng
            if not (lo <= hi) or step < 0:
                raise ConfigError(f"parameter descriptor: {what} {rng} needs from <= to and step >= 0")


def type_of(value: Any) -> str:
    """The ROS parameter type of a Python value (ValueError if no ROS type holds it)."""
    if value is None:
        return "not_set"
    if isinstance(value, bool):
        return "bool"
    if isinstance(value, int):
        return "integer"
    if isinstance(value, float):
        return "double"
    if isinstance(value, str):
        return "string"
    if isinstance(value, (bytes, bytearray)):
        return "byte_array"
    if isinstance(value, (list, tuple)):
        if not value:
            return "string_array"  # rclcpp cannot tell an empty YAML list's type either; string is the loosest
        if all(isinstance(v, bool) for v in value):
            return "bool_array"
        if all(isinstance(v, int) and not isinstance(v, bool) for v in value):
            return "integer_array"
        if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
            return "double_array"
        if all(isinstance(v, str) for v in value):
            return "string_array"
    raise ValueError(f"{value!r} is not a ROS parameter value (bool, integer, double, string or a list of one of them)")


def _coerce_declared(value: Any, want: str) -> Any:
    """An override's value as the declared type where that loses nothing (YAML `1` for a double)."""
    if want == "double" and isinstance(value, int) and not isinstance(value, bool):
        return float(value)
    if want == "double_array" and isinstance(value, (list, tuple)) and all(
        isinstance(v, (int, float)) and not isinstance(v, bool) for v in value
    ):
        return [float(v) for v in value]
    if want.endswith("_array") and isinstance(value, (list, tuple)) and not value:
        return []
    if isinstance(value, tuple):
        return list(value)
    return value


def _close(a: float, b: float) -> bool:
    return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)


def range_refusal(name: str, value: Any, desc: ParameterDescriptor) -> str | None:
    """rclcpp's range check: inclusive bounds, and with a step, a whole number of steps from `from` (or `to`)."""
    if desc.integer_range is not None and type_of(value) == "integer":
        lo, hi, step = desc.integer_range
        if value in (lo, hi):
            return None
        if value < lo or value > hi or (step and (value - lo) % step):
            return f"Parameter {{{name}}} doesn't comply with integer range."
    if desc.floating_point_range is not None and type_of(value) == "double":
        lo, hi, step = desc.floating_point_range
        if _close(value, lo) or _close(value, hi):
            return None
        if not math.isfinite(value) or value < lo or value > hi:
            return f"Parameter {{{name}}} doesn't comply with floating point range."
        if step:
            n = (value - lo) / step
            if not _close(n, round(n)):
                return f"Parameter {{{name}}} doesn't comply with floating point range."
    return None


@dataclass(frozen=True)
class ParameterChange:
    """One accepted change, for /parameter_events: kind is "new", "changed" or "deleted"."""

    kind: str
    name: str
    value: Any


class ParameterStore:
    """Declared parameters, their descriptors and current values; thread-safe.

    `values` is the dict the node exposes as `node.params`: changes are written into it in place, so code
    holding it sees them.
    """

    def __init__(self, values: dict[str, Any], *, allow_undeclared: bool = True) -> None:
        self.values = values
        self.overrides = dict(values)
        self.allow_undeclared = allow_undeclared
        self.descriptors: dict[str, ParameterDescriptor] = {}
        self._callbacks: list[Callable[[dict[str, Any]], str | None]] = []
        self._listeners: list[Callable[[list[ParameterChange]], None]] = []
        self._lock = threading.RLock()

    # ------------------------------------------------------------------ hooks
    def add_listener(self, listener: Callable[[list[ParameterChange]], None]) -> None:
        self._listeners.append(listener)

    def add_on_set_callback(self, cb: Callable[[dict[str, Any]], str | None]) -> None:
        self._callbacks.append(cb)

    def _notify(self, changes: list[ParameterChange]) -> None:
        for listener in list(self._listeners):
            listener(changes)

    # ------------------------------------------------------------------ declare, get
    def declare(self, name: str, default: Any, descriptor: ParameterDescriptor | None = None) -> Any:
        """Declare `name`; its value is the override if one was given, else `default`. Invalid → ConfigError."""
        desc = descriptor or ParameterDescriptor()
        if not name or name.startswith(".") or name.endswith(".") or ".." in name:
            raise ConfigError(f"invalid parameter name {name!r}",
                              hint="dot-separated words, e.g. linear.x.max_velocity")
        with self._lock:
            if name in self.descriptors:
                raise ConfigError(f"parameter '{name}' has already been declared")
            if desc.type is None:
                try:
                    desc = _with_type(desc, type_of(default))
                except ValueError as e:
                    raise ConfigError(f"parameter '{name}': default {e}") from None
            value = self.overrides.get(name, default)
            value = _coerce_declared(value, desc.type or "not_set")
            why = self._refusal(name, value, desc, initial=True)
            if why is not None:
                hint = _valid_text(desc)
                raise ConfigError(f"parameter '{name}' = {value!r}: {why}", hint=hint or None)
            for cb in list(self._callbacks):
                why = cb({name: value})
                if why:
                    raise ConfigError(f"parameter '{name}' = {value!r} refused: {why}")
            existed = name in self.values
            self.descriptors[name] = desc
            self.values[name] = value
        self._notify([ParameterChange("changed" if existed else "new", name, value)])
        return value

    def get(self, name: str) -> Any:
        with self._lock:
            if name not in self.values:
                raise KeyError(name)
            return self.values[name]

    def has(self, name: str) -> bool:
        return name in self.values

    def descriptor(self, name: str) -> ParameterDescriptor:
        """The declared descriptor, or for an undeclared override one typed by its value (dynamic, as rclcpp)."""
        with self._lock:
            if name in self.descriptors:
                return self.descriptors[name]
            try:
                return ParameterDescriptor(type=type_of(self.values.get(name)), dynamic_typing=True)
            except ValueError:
                return ParameterDescriptor(type="string", dynamic_typing=True)

    def names(self) -> list[str]:
        with self._lock:
            return sorted(self.values)

    # ------------------------------------------------------------------ set
    def _refusal(self, name: str, value: Any, desc: ParameterDescriptor, *, initial: bool = False) -> str | None:
        if desc.read_only and not initial:
            return f"parameter '{name}' cannot be set because it is read-only"
        try:
            got = type_of(value)
        except ValueError as e:
            return str(e)
        want = desc.type or "not_set"
        if got == "string_array" and not value and want.endswith("_array"):
            got = want  # an empty list fits any array type
        if not desc.dynamic_typing and got != want and want != "not_set" and got != "not_set":
            return (f"Wrong parameter type, parameter {{{name}}} is of type {{{_ROS_TYPE_WORD[want]}}}, "
                    f"setting it to {{{_ROS_TYPE_WORD[got]}}} is not allowed.")
        return range_refusal(name, value, desc)

    def _check(self, name: str, value: Any) -> str | None:
        if name in self.descriptors:
            return self._refusal(name, value, self.descriptors[name])
        if name not in self.values and not self.allow_undeclared:
            return f"parameter '{name}' cannot be set because it was not declared"
        if value is not None:
            try:
                type_of(value)
            except ValueError as e:
                return str(e)
        return None

    def set_atomically(self, changes: dict[str, Any]) -> str | None:
        """Apply all of `changes` or none; the refusal reason, or None when applied. None as a value deletes."""
        changes = {k: (list(v) if isinstance(v, tuple) else v) for k, v in changes.items()}
        with self._lock:
            for name, value in changes.items():
                why = self._check(name, value)
                if why is not None:
                    return why
                if value is None and self.descriptors.get(name, ParameterDescriptor()).read_only:
                    return f"cannot undeclare parameter '{name}' because it is read-only"
            for cb in list(self._callbacks):
                try:
                    why = cb(dict(changes))
                except Exception as e:  # a callback bug refuses the set rather than killing the service thread
                    why = f"{type(e).__name__}: {e}"
                if why:
                    return str(why)
            events: list[ParameterChange] = []
            for name, value in changes.items():
                if value is None:
                    if name in self.values:
                        del self.values[name]
                        self.descriptors.pop(name, None)
                        events.append(ParameterChange("deleted", name, None))
                    continue
                # An undeclared parameter set from outside is declared implicitly, as rclcpp does.
                kind = "changed" if name in self.values else "new"
                self.values[name] = value
                events.append(ParameterChange(kind, name, value))
        if events:
            self._notify(events)
        return None

    def set(self, changes: dict[str, Any]) -> list[str | None]:
        """`set_parameters`: each parameter on its own; per-parameter refusal reason or None."""
        return [self.set_atomically({name: value}) for name, value in changes.items()]

    # ------------------------------------------------------------------ list
    def list(self, prefixes: Iterable[str] = (), depth: int = 0) -> tuple[list[str], list[str]]:
        """rclcpp's list_parameters: (names, distinct parent prefixes) matching the prefixes and depth."""
        prefixes = list(prefixes)

        def under(name: str, p: str) -> bool:
            if name == p:
                return True
            # Dots after the prefix (its own separator included) must stay below `depth`.
            return name.startswith(p + ".") and (depth == 0 or name.count(".") - p.count(".") < depth)

        out = [
            n for n in self.names()
            if (not prefixes and (depth == 0 or n.count(".") < depth)) or any(under(n, p) for p in prefixes)
        ]
        parents = sorted({n.rpartition(".")[0] for n in out if "." in n})
        return out, parents


def _with_type(desc: ParameterDescriptor, type_name: str) -> ParameterDescriptor:
    # A parameter declared with no default (None) and no type takes any type, as rclcpp's dynamic typing.
    if type_name == "not_set":
        return replace(desc, type="not_set", dynamic_typing=True)
    return replace(desc, type=type_name)


def _valid_text(desc: ParameterDescriptor) -> str:
    parts = []
    if desc.type and desc.type != "not_set" and not desc.dynamic_typing:
        parts.append(("an " if desc.type[0] in "aeiou" else "a ") + desc.type)
    if desc.floating_point_range:
        lo, hi, step = desc.floating_point_range
        parts.append(f"in [{lo:g}, {hi:g}]" + (f" in steps of {step:g}" if step else ""))
    if desc.integer_range:
        lo, hi, step = desc.integer_range
        parts.append(f"in [{lo}, {hi}]" + (f" in steps of {step}" if step else ""))
    if desc.additional_constraints:
        parts.append(desc.additional_constraints)
    return ("valid: " + ", ".join(parts)) if parts else ""
