"""Whatever a gz sample holds, converting it gives a valid Jazzy message or a MessageError, nothing else."""

from __future__ import annotations

import pytest
from bridge_samples import GZ_SAMPLES
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from diffctl.bridge import type_pairs
from diffctl.bridge.bridge import _serialize
from diffctl.bus import gz
from diffctl.errors import MessageError

_leaf = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(min_value=-(2**70), max_value=2**70),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=8),
    st.binary(max_size=16),
)
_value = st.recursive(
    _leaf,
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=6), inner, max_size=4),
    max_leaves=12,
)


def _mutations(sample: dict) -> st.SearchStrategy[dict]:
    """The sample with some of its fields (also nested ones' parents) replaced by arbitrary values."""
    keys = sorted(sample) or ["data"]
    return st.dictionaries(st.sampled_from(keys), _value, max_size=len(keys)).map(lambda m: {**sample, **m})


@pytest.mark.parametrize(("ros_type", "gz_type"), sorted(GZ_SAMPLES))
def test_arbitrary_field_values_convert_or_raise_message_error(ros_type: str, gz_type: str) -> None:
    pair = type_pairs.lookup(ros_type, gz_type)

    @settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
    @given(_mutations(GZ_SAMPLES[(ros_type, gz_type)]))
    def check(fields: dict) -> None:
        try:
            _, decoded = gz.decode(gz.encode(gz_type, fields), gz_type)
            _serialize(pair.convert_to_ros(decoded), ros_type)
        except MessageError:
            pass

    check()
