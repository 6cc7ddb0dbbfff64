"""Typed reading of a controller's flattened parameters, with one error style for every bad value.

Controllers build their frozen parameter dataclasses through a `ParamReader`: each getter checks type and
range and raises ParameterError naming `<controller>.<parameter>`, quoting the value and saying what would
be valid. Integers are accepted where a double is expected (rclcpp would refuse `wheel_radius: 1`; nobody
means anything else by it). The reader remembers which keys it was asked about, so keys nobody asked for
become "unknown parameter" warnings with a did-you-mean.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import Any

from diffctl.errors import ParameterError, suggest

# Keys the controller manager declares on every controller node (ros2_control's auto-declared ones).
MANAGER_KEYS = frozenset(
    {"type", "update_rate", "use_sim_time", "params_file", "is_async", "thread_priority", "fallback_controllers"}
)


def _is_number(value: Any) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


class ParamReader:
    """Typed getters over `params` for controller `controller`; see the module docstring."""

    def __init__(self, params: Mapping[str, Any], controller: str) -> None:
        self.params = params
        self.controller = controller
        self.asked: set[str] = set()

    def field(self, key: str) -> str:
        return f"{self.controller}.{key}"

    def error(self, key: str, message: str, hint: str | None = None) -> ParameterError:
        return ParameterError(message, field=self.field(key), hint=hint)

    def has(self, key: str) -> bool:
        self.asked.add(key)
        return key in self.params

    def _get(self, key: str, default: Any) -> Any:
        self.asked.add(key)
        return self.params.get(key, default)

    # --- scalars ---------------------------------------------------------------------------------------------
    def float(
        self,
        key: str,
        default: float,
        *,
        gt: float | None = None,
        ge: float | None = None,
        le: float | None = None,
        allow_nan: bool = False,
        allow_inf: bool = False,
        what: str = "",
    ) -> float:
        raw = self._get(key, default)
        if not _is_number(raw):
            raise self.error(key, f"{raw!r} is not a number{what_suffix(what)}")
        value = float(raw)
        if math.isnan(value):
            if allow_nan:
                return value
            raise self.error(key, f"{raw!r} is not allowed here{what_suffix(what)}", "give a finite number")
        if math.isinf(value) and not allow_inf:
            raise self.error(key, f"{raw!r} is not a finite number{what_suffix(what)}")
        if gt is not None and not value > gt:
            raise self.error(key, f"{raw!r} must be > {gt:g}{what_suffix(what)}")
        if ge is not None and not value >= ge:
            raise self.error(key, f"{raw!r} must be ≥ {ge:g}{what_suffix(what)}")
        if le is not None and not value <= le:
            raise self.error(key, f"{raw!r} must be ≤ {le:g}{what_suffix(what)}")
        return value

    def int(self, key: str, default: int, *, ge: int | None = None, le: int | None = None) -> int:
        value = self._get(key, default)
        if isinstance(value, float) and math.isfinite(value) and value.is_integer():
            value = int(value)
        if not isinstance(value, int) or isinstance(value, bool):
            raise self.error(key, f"{value!r} is not an integer")
        if ge is not None and value < ge:
            raise self.error(key, f"{value!r} must be ≥ {ge}")
        if le is not None and value > le:
            raise self.error(key, f"{value!r} must be ≤ {le}")
        return value

    def bool(self, key: str, default: bool) -> bool:
        value = self._get(key, default)
        if not isinstance(value, bool):
            raise self.error(key, f"{value!r} is not a bool", "write true or false")
        return value

    def str(self, key: str, default: str, *, non_empty: bool = False, choices: Iterable[str] | None = None) -> str:
        value = self._get(key, default)
        if not isinstance(value, str):
            raise self.error(key, f"{value!r} is not a string")
        if non_empty and not value.strip():
            raise self.error(key, f"{value!r} must not be empty")
        if choices is not None:
            options = list(choices)
            if value not in options:
                raise self.error(key, f"{value!r} is not one of {options}{suggest(value, options)}")
        return value

    # --- lists -----------------------------------------------------------------------------------------------
    def str_list(self, key: str, default: list[str], *, non_empty: bool = False) -> tuple[str, ...]:
        value = self._get(key, default)
        if isinstance(value, tuple):
            value = list(value)
        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            raise self.error(key, f"{value!r} is not a list of strings", 'write e.g. ["joint_a", "joint_b"]')
        if non_empty and not value:
            raise self.error(key, f"{value!r} must list at least one name")
        blank = [v for v in value if not v.strip()]
        if blank:
            raise self.error(key, f"{value!r} contains an empty name")
        dups = sorted({v for v in value if value.count(v) > 1})
        if dups:
            raise self.error(key, f"{value!r} names {dups[0]!r} more than once")
        return tuple(value)

    def float_list(
        self, key: str, default: list[float], *, length: int | None = None, ge: float | None = None
    ) -> tuple[float, ...]:
        value = self._get(key, default)
        if isinstance(value, tuple):
            value = list(value)
        if not isinstance(value, list) or not all(_is_number(v) for v in value):
            raise self.error(key, f"{value!r} is not a list of numbers")
        if length is not None and len(value) != length:
            raise self.error(key, f"{value!r} has {len(value)} entries, expected {length}")
        for v in value:
            if not math.isfinite(v):
                raise self.error(key, f"{value!r} contains {v!r}: every entry must be finite")
            if ge is not None and v < ge:
                raise self.error(key, f"{value!r} contains {v!r}: every entry must be ≥ {ge:g}")
        return tuple(float(v) for v in value)

    # --- leftovers -------------------------------------------------------------------------------------------
    def unknown_key_warnings(self, also_known: Iterable[str] = ()) -> list[str]:
        """One warning per key in `params` that no getter asked for (and that the manager does not own)."""
        known = self.asked | MANAGER_KEYS | set(also_known)
        out = []
        for key in self.params:
            if key not in known:
                out.append(f"unknown parameter {self.field(key)!r} is ignored{suggest(key, sorted(known))}")
        return out


def what_suffix(what: str) -> str:
    return f" ({what})" if what else ""
