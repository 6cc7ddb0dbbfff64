"""A filter chain configured from a node's parameters as the filters library (2.1) configures one.

`filter1.name` and `filter1.type`, `filter2.…`, … are read until a number has neither; each pair must be
strings, names unique, types `<package>/<Filter>`, and is then redeclared read-only. Each filter's parameters are
`filterN.params.<name>`, declared read-only with the type the filter reads. A chain runs its filters in turn;
one that fails stops it.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from diffctl.errors import ConfigError
from diffctl.laser_filters.filters import FILTERS, NOT_PROVIDED
from diffctl.laser_filters.scan import Scan

STRING = 4
TYPE_CODES = {bool: 1, int: 2, float: 3, str: 4}


def _descriptor(**fields: Any) -> Any:
    from diffctl.interfaces import get_interface

    return get_interface("rcl_interfaces/msg/ParameterDescriptor")(**fields)


def read_chain(node: Any) -> list[tuple[str, str, str]]:
    """(name, type, parameter prefix) of each filter the parameters list."""
    found: list[tuple[str, str, str]] = []
    number = 1
    while True:
        keys = (f"filter{number}.name", f"filter{number}.type")
        values = [node.declare_parameter(k, None, _descriptor(name=k, type=STRING, dynamic_typing=True)).value
                  for k in keys]
        if values == [None, None]:
            return found
        if None in values:
            raise ConfigError(f"{keys[0]} and {keys[1]} are required")
        for key, value in zip(keys, values, strict=True):
            if not isinstance(value, str):
                raise ConfigError(f"{key} must be a string (got {value!r})")
        name, kind = values
        if any(name == other for other, _, _ in found):
            raise ConfigError(f"A filter with the name {name} already exists")
        if kind.count("/") != 1:
            raise ConfigError(f"{kind} must be of form <package_name>/<filter_name>", field=keys[1])
        for key, value in zip(keys, values, strict=True):
            node.undeclare_parameter(key)
            node.declare_parameter(key, value, _descriptor(name=key, type=STRING, read_only=True))
        found.append((name, kind, f"filter{number}.params"))
        number += 1


def build(node: Any, make_extra: Callable[[type], dict[str, Any]] | None = None) -> list[tuple[str, Any]]:
    """The configured filters, in chain order. `make_extra(cls)`: further constructor arguments (the box
    filter's transforms)."""
    filters = []
    for name, kind, prefix in read_chain(node):
        cls = FILTERS.get(kind)
        if cls is None:
            known = ", ".join(FILTERS)
            why = "is one of laser_filters' filters diffctl does not provide" if kind in NOT_PROVIDED \
                else "is no filter diffctl knows"
            raise ConfigError(f"Could not load library for {kind}: it {why}", field=f"{prefix[:-7]}.type",
                              hint=f"diffctl provides {known}")
        values = {}
        for param, default in cls.PARAMS:
            key = f"{prefix}.{param}"
            values[param] = node.declare_parameter(
                key, default, _descriptor(name=param, type=TYPE_CODES[type(default)], read_only=True)).value
        extra = make_extra(cls) if make_extra is not None else {}
        filters.append((name, cls(values, node.get_logger(), **extra)))
    return filters


def update(filters: list[tuple[str, Any]], scan: Scan) -> Scan | None:
    for _, f in filters:
        result = f.update(scan)
        if result is None:
            return None
        scan = result
    return scan
