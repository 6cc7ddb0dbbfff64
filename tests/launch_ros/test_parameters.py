"""Node parameters as launch_ros types them: plain values kept, substituted text read as YAML (scalars and uniform
lists only), strings kept as strings; parameter files with substitutions; files read for one node."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.substitutions import EnvironmentVariable, TextSubstitution
from diffctl.launch_ros.descriptions import ParameterFile, ParameterValue
from diffctl.launch_ros.utilities import evaluate_parameters, normalize_parameters, to_parameters_list


def T(text: str) -> TextSubstitution:
    return TextSubstitution(text=text)


@pytest.mark.parametrize(
    ("value", "evaluated"),
    [
        (1, 1),
        ("1", "1"),  # a Python string stays a string
        (T("1"), 1),  # substituted text is read as YAML
        (T("off"), False),
        (T(""), ""),
        ([1, 2.5], (1.0, 2.5)),  # ints and floats make floats
        (["a", T("b")], "ab"),  # text with substitutions is one string
        ([[T("1")], [T("2")]], (1, 2)),  # a list of substituted items
        (T("[true, false]"), (True, False)),
        (ParameterValue(T("[1, 2]"), value_type=str), "[1, 2]"),
        # diffctl: text that is no YAML at all (an SDF read by `let file`) is the string, where ROS fails
        (
            ParameterValue(T("<sdf>\n<!-- car: a two-wheel: drive -->\n</sdf>")),
            "<sdf>\n<!-- car: a two-wheel: drive -->\n</sdf>",
        ),
        (ParameterValue(T("2.5")), 2.5),
        (b"\x00\xff", b"\x00\xff"),
    ],
)
def test_values_are_typed_as_launch_ros_types_them(value: object, evaluated: object) -> None:
    (result,) = evaluate_parameters(LaunchContext(), normalize_parameters([{"group": {"p": value}}]))
    assert result == {"group.p": evaluated}


@pytest.mark.parametrize(
    ("value", "message"),
    [
        (T("[1, a]"), "Expected a non-empty sequence"),
        (T("[]"), "Expected a non-empty sequence"),
        (T("{a: 1}"), "Allowed value types are"),
        (T("a: b: c"), "Unable to parse the value of parameter p as yaml"),
        ([True, 1], "Expected a non-empty sequence"),
    ],
)
def test_what_a_node_parameter_cannot_be_is_a_type_error(value: object, message: str) -> None:
    with pytest.raises(TypeError, match=message):
        evaluate_parameters(LaunchContext(), normalize_parameters([{"p": value}]))


@pytest.mark.parametrize("bad", [{"p": [1, [2]]}, {"p": {1, 2}}, {5: "x"}])
def test_malformed_dictionaries_are_refused_when_given(bad: dict) -> None:
    with pytest.raises(TypeError):
        normalize_parameters([bad])


def test_a_parameter_file_with_substitutions_is_substituted_into_a_copy(tmp_path: Path, monkeypatch) -> None:
    monkeypatch.setenv("L2_ROBOT", "r1")
    source = tmp_path / "params.yaml"
    source.write_text("/$(env L2_ROBOT)/driver:\n  ros__parameters:\n    name: '$(env L2_ROBOT)'\n")
    plain, substituted = ParameterFile(source), ParameterFile(str(source), allow_substs=True)
    context = LaunchContext()
    assert plain.evaluate(context) == source
    copy = substituted.evaluate(context)
    assert copy != source
    assert copy.read_text() == "/r1/driver:\n  ros__parameters:\n    name: 'r1'\n"
    substituted.cleanup()
    assert not copy.exists() and source.exists()


def test_a_file_gives_a_loaded_node_its_wildcard_then_its_own_section(tmp_path: Path) -> None:
    source = tmp_path / "params.yaml"
    source.write_text(
        "/**:\n  ros__parameters:\n    rate: 1\n    frame: odom\n"
        "/ns/driver:\n  ros__parameters:\n    rate: 5\n"
        "/other:\n  ros__parameters:\n    rate: 9\n"
    )
    context = LaunchContext()
    given = normalize_parameters([source, {"extra": EnvironmentVariable("HOME")}])
    parameters = to_parameters_list(context, "driver", "/ns", evaluate_parameters(context, given))
    assert [(p.name, p.value) for p in parameters] == [("rate", 5), ("frame", "odom"), ("extra", os.environ["HOME"])]
