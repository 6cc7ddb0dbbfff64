"""The sim-side binary encoding (diffctl.bus.gz): MessagePack `[type, fields]`, raw bytes, packed arrays."""

from __future__ import annotations

import json
import math

import msgpack
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from diffctl.bus import gz
from diffctl.errors import MessageError


def test_a_sample_is_plain_msgpack_of_type_and_fields() -> None:
    fields = {"header": gz.header(5, frame_id="odom"), "linear": {"x": 0.5}, "angular": {"z": -1.0}}
    payload = gz.encode("gz.msgs.Twist", fields)
    # Any MessagePack reader sees the two-element array; no private framing.
    assert msgpack.unpackb(payload) == ["gz.msgs.Twist", fields]
    assert gz.decode(payload, "gz.msgs.Twist") == ("gz.msgs.Twist", fields)


def test_bytes_travel_raw_and_numeric_arrays_keep_their_dtype() -> None:
    pixels = bytes(range(256)) * 40
    ranges = np.array([0.5, math.inf, -math.inf, math.nan, 12.25], dtype=np.float32)
    ring = np.arange(7, dtype=np.uint16)
    payload = gz.encode("gz.msgs.X", {"data": pixels, "ranges": ranges, "ring": ring, "k": [1.0, 2.0]})
    assert pixels in payload and ranges.astype("<f4").tobytes() in payload  # no base64, no per-element framing
    assert len(payload) < len(pixels) + ranges.nbytes + ring.nbytes + 100
    _, out = gz.decode(payload)
    assert out["data"] == pixels
    assert out["ranges"].dtype == np.float32 and out["ring"].dtype == np.uint16
    np.testing.assert_array_equal(out["ranges"], ranges)  # NaN and ±inf survive
    assert out["ring"].tolist() == list(range(7)) and out["k"] == [1.0, 2.0]


def test_numpy_scalars_and_byte_views_encode_as_plain_values() -> None:
    _, out = gz.decode(gz.encode("gz.msgs.X", {"a": np.float32(1.5), "n": np.int64(-3), "b": np.bool_(True)}))
    assert out == {"a": 1.5, "n": -3, "b": True}
    _, out = gz.decode(gz.encode("gz.msgs.X", {"data": memoryview(b"xyz"), "more": bytearray(b"q")}))
    assert out == {"data": b"xyz", "more": b"q"}


def test_clock_is_the_encoding_of_its_dict_and_smaller_than_json() -> None:
    payload = gz.clock(12_345_000_001, 2_000_000_007, 1_700_000_000_123_456_789)
    fields = {
        "header": {"stamp": {"sec": 12, "nsec": 345_000_001}, "data": []},
        "sim": {"sec": 12, "nsec": 345_000_001},
        "real": {"sec": 2, "nsec": 7},
        "system": {"sec": 1_700_000_000, "nsec": 123_456_789},
    }
    assert payload == gz.encode("gz.msgs.Clock", fields)
    assert gz.decode(payload, "gz.msgs.Clock")[1] == fields
    assert len(payload) < len(json.dumps({"@type": "gz.msgs.Clock", **fields}, separators=(",", ":")))


def test_unexpected_type_and_wrong_shapes_are_message_errors() -> None:
    with pytest.raises(MessageError, match=r"gz message of type gz\.msgs\.Twist, expected gz\.msgs\.Clock"):
        gz.decode(gz.encode("gz.msgs.Twist", {}), "gz.msgs.Clock")
    for shape in (["gz.msgs.Clock"], {"@type": "gz.msgs.Clock"}, [1, {}], ["gz.msgs.Clock", []], 7):
        with pytest.raises(MessageError, match="not a \\[type, fields\\] pair"):
            gz.decode(msgpack.packb(shape))
    with pytest.raises(MessageError, match="malformed gz message"):
        gz.decode(b'{"@type":"gz.msgs.Clock"}' + b"\xc1")  # JSON of the old encoding, plus a reserved byte
    with pytest.raises(MessageError, match="unknown extension type"):
        gz.decode(msgpack.packb(["gz.msgs.X", {"a": msgpack.ExtType(9, b"\x00")}]))
    with pytest.raises(MessageError, match="array of"):
        gz.decode(msgpack.packb(["gz.msgs.X", {"a": msgpack.ExtType(gz.ARRAY_EXT, b"\x00abc")}]))
    with pytest.raises(MessageError, match=r"cannot encode gz\.msgs\.X"):
        gz.encode("gz.msgs.X", {"a": object()})
    with pytest.raises(MessageError, match="no gz encoding"):
        gz.encode("gz.msgs.X", {"a": np.array(["text"])})


@settings(max_examples=400, deadline=None)
@given(st.binary(max_size=200))
def test_any_bytes_decode_or_raise_message_error(payload: bytes) -> None:
    try:
        gz_type, fields = gz.decode(payload)
    except MessageError:
        return
    assert isinstance(gz_type, str) and isinstance(fields, dict)
