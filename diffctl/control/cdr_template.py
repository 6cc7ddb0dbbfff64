"""A message whose layout does not change from cycle to cycle, serialized by one `struct.pack`.

Controllers publish the same message every cycle with only a few numbers changed (the stamp, joint
values, the pose): names, frame ids, covariances and sequence lengths are fixed once they are activated.
Serializing the whole tree each cycle walks every field; here the CDR bytes of the message are taken once,
the place of every changing field (a *leaf*) is found in them, and a cycle packs the leaves' new values
between the constant stretches in a single `struct.Struct.pack` call.

A leaf's place is found by changing it and serializing again (no knowledge of CDR's layout is repeated
here), and the result is checked against the client's serializer for every leaf at build time: a template
that would give other bytes than `serialize` raises instead of being used.
"""

from __future__ import annotations

import re
import struct
from collections.abc import Sequence
from typing import Any

_HEADER = 4  # CDR's encapsulation header; primitives align to their size from the byte after it
_PART = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)((?:\[\d+\])*)")


class TemplateError(Exception):
    """The message cannot be served by a template (a leaf's bytes could not be told apart)."""


def _resolve(msg: Any, path: str) -> tuple[Any, Any]:
    """(container, key) of the leaf at `path` ("header.stamp.sec", "interface_values[1].values[0]")."""
    parts = path.split(".")
    obj = msg
    for i, part in enumerate(parts):
        m = _PART.fullmatch(part)
        if m is None:
            raise TemplateError(f"bad leaf path {path!r}")
        name, subscripts = m.group(1), [int(x) for x in re.findall(r"\[(\d+)\]", m.group(2))]
        last = i == len(parts) - 1
        if last and not subscripts:
            return obj, name
        obj = getattr(obj, name)
        for k, index in enumerate(subscripts):
            if last and k == len(subscripts) - 1:
                return obj, index
            obj = obj[index]
    raise TemplateError(f"bad leaf path {path!r}")


def _get(container: Any, key: Any) -> Any:
    return getattr(container, key) if isinstance(key, str) else container[key]


def _set(container: Any, key: Any, value: Any) -> None:
    if isinstance(key, str):
        setattr(container, key, value)
    else:
        container[key] = value


def _probe_value(code: str, current: Any, i: int) -> Any:
    """A value for leaf `i` that differs from its current one and from the other leaves' probes."""
    if code in "fd":
        v = 1234.5 + 0.125 * i
        return v + 1.0 if v == current else v
    v = 10_000 + i
    return v + 1 if v == current else v


class CdrTemplate:
    """`encode(values)` → the CDR bytes of `msg` (as it was at build time) with its leaves set to `values`.

    `leaves` are (path, struct code) in the order of the message's bytes, e.g. ("header.stamp.sec", "i"),
    ("header.stamp.nanosec", "I"), ("pose.pose.position.x", "d"). Everything else must stay as it is in
    `msg` for as long as the template is used (rebuild it when a name or a sequence length changes).
    """

    def __init__(self, msg: Any, typename: str, leaves: Sequence[tuple[str, str]]) -> None:
        from diffctl.client.interfaces import serialize

        self.typename = typename
        self.leaves = tuple(leaves)
        places = [_resolve(msg, path) for path, _ in self.leaves]
        saved = [_get(c, k) for c, k in places]
        base = serialize(msg)
        offsets: list[int] = []
        try:
            for i, ((path, code), (c, k)) in enumerate(zip(self.leaves, places, strict=True)):
                _set(c, k, _probe_value(code, saved[i], i))
                try:
                    probed = serialize(msg)
                except Exception as e:  # the field does not take this kind of value
                    raise TemplateError(f"{typename}: {path} is not a {code!r} field: {e}") from e
                finally:
                    _set(c, k, saved[i])
                if len(probed) != len(base):
                    raise TemplateError(f"{typename}: changing {path} changes the message's length")
                changed = [j for j in range(len(base)) if base[j] != probed[j]]
                size = struct.calcsize("<" + code)
                if not changed:
                    raise TemplateError(f"{typename}: {path} does not show in the bytes")
                start = _HEADER + (changed[0] - _HEADER) // size * size
                if changed[-1] >= start + size:
                    raise TemplateError(f"{typename}: {path} is not one {code!r} field")
                offsets.append(start)
        finally:
            for (c, k), v in zip(places, saved, strict=True):
                _set(c, k, v)
        # Format: constant bytes, leaf, constant bytes, leaf, …, constant bytes ("0s" where leaves touch), so
        # the arguments alternate and a cycle only writes the odd positions of one prepared list.
        fmt = ["<"]
        args: list[Any] = []
        pos = 0
        for (path, code), off in zip(self.leaves, offsets, strict=True):
            if off < pos:
                raise TemplateError(f"{typename}: leaves out of order or overlapping at {path}")
            fmt.append(f"{off - pos}s{code}")
            args += [base[pos:off], None]
            pos = off + struct.calcsize("<" + code)
        fmt.append(f"{len(base) - pos}s")
        args.append(base[pos:])
        self._struct = struct.Struct("".join(fmt))
        self._args = args
        self.size = len(base)
        self._check(msg, places, saved, base)

    def _check(self, msg: Any, places: list[tuple[Any, Any]], saved: list[Any], base: bytes) -> None:
        from diffctl.client.interfaces import serialize

        if self.encode(saved) != base:
            raise TemplateError(f"{self.typename}: the template does not reproduce the message")
        probes = [_probe_value(code, v, i) for i, ((_, code), v) in enumerate(zip(self.leaves, saved, strict=True))]
        try:
            for (c, k), p in zip(places, probes, strict=True):
                _set(c, k, p)
            expected = serialize(msg)
        finally:
            for (c, k), v in zip(places, saved, strict=True):
                _set(c, k, v)
        if self.encode(probes) != expected:
            raise TemplateError(f"{self.typename}: the template's leaves do not match the serializer's")

    def encode(self, values: Sequence[Any]) -> bytes:
        """The message's bytes with the leaves set to `values` (in the order given at build time); safe to
        call from several threads (the controllers' publishing thread packs, tests compare)."""
        args = self._args.copy()
        args[1::2] = values
        return self._struct.pack(*args)
