"""ROS namespace arithmetic: absolute or relative, joined onto a pushed namespace."""

from __future__ import annotations

from typing import TypeVar

OptionalText = TypeVar("OptionalText", str, None)


def is_root_namespace(ns: str) -> bool:
    """True for `/`."""
    return ns == "/"


def is_namespace_absolute(ns: str) -> bool:
    """True when `ns` starts at the root."""
    return ns.startswith("/")


def prefix_namespace(base_ns: str | None, ns: str | None) -> str | None:
    """`ns` under `base_ns` unless `ns` is absolute; either may be None (then the other is the result).

    The result keeps no trailing `/` (except the root itself): `prefix_namespace('a', 'b') == 'a/b'`,
    `prefix_namespace('/a', 'b') == '/a/b'`, `prefix_namespace('a', '/b') == '/b'`.
    """
    if ns is None:
        combined = base_ns
    elif not base_ns or is_namespace_absolute(ns):
        combined = ns
    else:
        combined = ("" if is_root_namespace(base_ns) else base_ns) + "/" + ns
    if combined is None or is_root_namespace(combined):
        return combined
    return combined.rstrip("/")


def make_namespace_absolute(ns: OptionalText) -> OptionalText:
    """`ns` with a leading `/` (None stays None)."""
    if ns is None or is_namespace_absolute(ns):
        return ns
    return "/" + ns
