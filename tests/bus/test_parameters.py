"""A node's parameter store: declare with overrides, types, ranges, read-only, callbacks, list depth, events."""

from __future__ import annotations

import pytest

from diffctl.bus.parameters import ParameterChange, ParameterDescriptor, ParameterStore
from diffctl.errors import ConfigError


def test_declare_takes_the_override_and_checks_it() -> None:
    values = {"max_velocity": 2, "name": "x"}
    s = ParameterStore(values)
    # A YAML integer for a double parameter is taken as the double it means.
    assert s.declare("max_velocity", 1.0, ParameterDescriptor(floating_point_range=(0.0, 5.0, 0.0))) == 2.0
    assert values["max_velocity"] == 2.0 and isinstance(values["max_velocity"], float)
    assert s.declare("rate", 50) == 50
    with pytest.raises(ConfigError, match="comply with integer range"):
        ParameterStore({"n": 7}).declare("n", 1, ParameterDescriptor(integer_range=(0, 10, 2)))
    with pytest.raises(ConfigError, match=r"is of type \{integer\}"):
        ParameterStore({"n": "seven"}).declare("n", 1)
    with pytest.raises(ConfigError, match="already been declared"):
        s.declare("rate", 1)


def test_set_rules_type_read_only_range_and_undeclared() -> None:
    s = ParameterStore({"legacy": "kept"}, allow_undeclared=True)
    s.declare("v", 1.0, ParameterDescriptor(floating_point_range=(0.0, 2.0, 0.5)))
    s.declare("frozen", "a", ParameterDescriptor(read_only=True))
    s.declare("anything", 1, ParameterDescriptor(dynamic_typing=True))
    assert s.set({"v": 1.5}) == [None]
    reasons = s.set({"v": 1.2, "frozen": "b", "anything": "text", "legacy": 3})
    assert "floating point range" in reasons[0]
    assert "read-only" in reasons[1]
    assert reasons[2:] == [None, None]
    assert s.get("v") == 1.5 and s.get("frozen") == "a" and s.get("anything") == "text"
    assert "is of type {double}" in s.set({"v": 1})[0]
    assert s.set({"v": 2.0}) == [None], "the upper bound is always allowed"
    strict = ParameterStore({}, allow_undeclared=False)
    assert "not declared" in strict.set({"ghost": 1})[0]


def test_atomic_set_and_callbacks_refuse_as_a_whole() -> None:
    s = ParameterStore({})
    s.declare("a", 1)
    s.declare("b", 2)
    seen: list[dict] = []
    s.add_on_set_callback(lambda ch: seen.append(ch) or ("b must stay even" if ch.get("b", 0) % 2 else None))
    assert s.set_atomically({"a": 5, "b": 3}) == "b must stay even"
    assert (s.get("a"), s.get("b")) == (1, 2)
    assert s.set_atomically({"a": 5, "b": 4}) is None
    assert (s.get("a"), s.get("b")) == (5, 4)
    assert seen[-1] == {"a": 5, "b": 4}


def test_events_and_undeclare() -> None:
    s = ParameterStore({})
    events: list[list[ParameterChange]] = []
    s.add_listener(events.append)
    s.declare("p", 1)
    s.set({"p": 2})
    s.set({"p": None})
    assert [(e.kind, e.name, e.value) for batch in events for e in batch] == [
        ("new", "p", 1), ("changed", "p", 2), ("deleted", "p", None)
    ]
    assert not s.has("p")


def test_list_prefixes_and_depth_as_rclcpp() -> None:
    s = ParameterStore({"a": 1, "a.b": 2, "a.b.c": 3, "ab": 4, "z.y": 5})
    assert s.list() == (["a", "a.b", "a.b.c", "ab", "z.y"], ["a", "a.b", "z"])
    assert s.list([], 1)[0] == ["a", "ab"]
    assert s.list(["a"])[0] == ["a", "a.b", "a.b.c"]
    assert s.list(["a"], 2)[0] == ["a", "a.b"]


def test_descriptor_is_validated() -> None:
    with pytest.raises(ConfigError, match="mutually exclusive"):
        ParameterDescriptor(floating_point_range=(0, 1, 0), integer_range=(0, 1, 0))
    with pytest.raises(ConfigError, match="unknown type"):
        ParameterDescriptor(type="float")


def test_an_empty_list_fits_any_array_type() -> None:
    s = ParameterStore({"joints": []})
    assert s.declare("joints", ["a"], ParameterDescriptor(type="string_array")) == []
    s.declare("gains", [1.0, 2.0])
    assert s.set({"gains": []}) == [None]
    assert "is of type {double_array}" in s.set({"gains": ["x"]})[0]
