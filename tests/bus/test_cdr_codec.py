"""The compiled CDR codec (diffctl/interfaces/cdr.py) against rosbags' own serializer, on every type of the store.

rosbags is the oracle: for default and randomly filled messages of each type, our bytes must equal its bytes,
our decoding of its bytes must equal its decoding, and no truncation or corruption may raise anything but
MessageError.
"""

from __future__ import annotations

import random
from typing import Any

import numpy as np
import pytest
from rosbags.typesys.base import Nodetype

from diffctl.errors import MessageError
from diffctl.interfaces import types

ALL_TYPES = [t for t in types.known_types() if "/srv/" not in t or t.endswith(("_Request", "_Response"))]
_INT = {"byte": (0, 127), "char": (0, 127), "int8": (-128, 127), "uint8": (0, 255), "int16": (-(2**15), 2**15 - 1),
        "uint16": (0, 2**16 - 1), "int32": (-(2**31), 2**31 - 1), "uint32": (0, 2**32 - 1),
        "int64": (-(2**63), 2**63 - 1), "uint64": (0, 2**64 - 1)}
_TEXT = ["", "a", "base_link", "ünïcødé ✓", "x" * 13]


def _random_value(desc: tuple, rng: random.Random, depth: int) -> Any:
    kind, spec = desc
    if kind == Nodetype.BASE:
        base = spec[0]
        if base in ("string", "wstring"):
            return rng.choice(_TEXT)
        if base == "bool":
            return rng.random() < 0.5
        if base in ("float32", "float64"):
            return float(np.float32(rng.uniform(-1e3, 1e3))) if base == "float32" else rng.uniform(-1e9, 1e9)
        return rng.randint(*_INT[base])
    if kind == Nodetype.NAME:
        return _random_dict(spec, rng, depth + 1)
    sub, count = spec
    if kind == Nodetype.SEQUENCE:
        count = rng.randint(0, min(count, 3) if count else 3) if depth < 3 else 0
    return [_random_value(sub, rng, depth + 1) for _ in range(count)]


def _random_dict(typename: str, rng: random.Random, depth: int = 0) -> dict[str, Any]:
    defs = types.store_with(typename).fielddefs[typename][1]
    return {name: _random_value(desc, rng, depth) for name, desc in defs}


def _messages(typename: str) -> list[Any]:
    rng = random.Random(typename)
    return [types.new(typename, {})] + [types.new(typename, _random_dict(typename, rng)) for _ in range(2)]


def _same(a: Any, b: Any) -> bool:
    # repr, so that a corrupted float that became NaN compares equal to the oracle's NaN.
    return repr(types.to_dict(a)) == repr(types.to_dict(b)) and type(a) is type(b)


@pytest.mark.parametrize("typename", ALL_TYPES)
def test_bytes_and_messages_equal_rosbags(typename: str) -> None:
    ts = types.store_with(typename)
    for msg in _messages(typename):
        theirs = bytes(ts.serialize_cdr(msg, typename))
        assert types.serialize(msg, typename) == theirs
        ours, oracle = types.deserialize(theirs, typename), ts.deserialize_cdr(theirs, typename)
        assert _same(ours, oracle)
        assert list(vars(ours)) == list(vars(oracle))  # the same instance state, as if built by __init__
        # Primitive arrays come back as numpy arrays of rosbags' dtypes, not lists.
        for name, _ in ts.fielddefs[typename][1]:
            a, b = getattr(ours, name), getattr(oracle, name)
            assert (type(a), getattr(a, "dtype", None)) == (type(b), getattr(b, "dtype", None)), name


@pytest.mark.parametrize("typename", ALL_TYPES)
def test_truncated_or_corrupt_samples_are_message_errors(typename: str) -> None:
    ts = types.store_with(typename)
    rng = random.Random(f"corrupt {typename}")
    raw = bytes(ts.serialize_cdr(types.new(typename, _random_dict(typename, rng)), typename))
    cuts = range(len(raw)) if len(raw) <= 32 else sorted(rng.sample(range(len(raw)), 32))
    variants = [raw[:n] for n in cuts]
    for _ in range(8):
        b = bytearray(raw)
        b[rng.randrange(4, len(b))] = rng.randrange(256)
        variants.append(bytes(b))
    for data in variants:
        try:
            ours = types.deserialize(data, typename)
        except MessageError:
            continue
        # Accepted: then rosbags reads the same message from it (e.g. a cut that only removed trailing padding).
        assert _same(ours, ts.deserialize_cdr(data, typename))


def test_big_endian_samples_still_decode() -> None:
    typename = "geometry_msgs/msg/TwistStamped"
    ts = types.store_with(typename)
    msg = types.new(typename, {"header": {"frame_id": "odom"}, "twist": {"angular": {"z": -0.25}}})
    raw = bytes(ts.serialize_cdr(msg, typename, little_endian=False))
    assert raw[:2] == b"\x00\x00"
    assert _same(types.deserialize(raw, typename), msg)
    assert _same(types.deserialize(memoryview(types.serialize(msg, typename)), typename), msg)
    # Writers may count their end padding in the encapsulation options (XCDR); the body is read the same.
    padded = types.serialize(msg, typename)
    assert _same(types.deserialize(padded[:2] + b"\x00\x03" + padded[4:], typename), msg)
