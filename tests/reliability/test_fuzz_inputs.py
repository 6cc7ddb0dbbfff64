"""Bad input, property-based: every file or value a user hands diffctl either works or fails with the project's
own error type and a message — never another exception (a traceback), a hang or a native crash.

Inputs are the project's real files, mutated (cut short, spans deleted, numbers and words replaced), plus
structured documents built from the real keys and tags mixed with wrong ones. Example counts are moderate
(CI budget): 100 per file kind, 150 for message values and payloads.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from diffctl.bridge.config import KEYS, load_config, parse_cli_entry
from diffctl.cli.bus_common import parse_values
from diffctl.control.controllers.diff_drive_params import DiffDriveParams
from diffctl.description.ros2_control import ros2_control_blocks
from diffctl.description.sdf_loader import parse_model, parse_world
from diffctl.errors import DiffctlError
from diffctl.interfaces import types
from diffctl.testing.loader import LaunchTestError, describe
from diffctl.testing.loader import load as load_launch_test

REPO = Path(__file__).resolve().parents[2]
SDF_TEXT = (REPO / "description" / "my_diff_car_control.sdf").read_text()
WORLD_TEXT = (REPO / "config" / "worlds" / "empty.world").read_text()
LAUNCH_TEXT = (REPO / "launch" / "sim_control.yaml").read_text()
BRIDGE_TEXT = (REPO / "config" / "bridge_config_control.yaml").read_text()
DIFF_PARAMS: dict[str, Any] = yaml.safe_load((REPO / "config" / "diff_drive_controller.yaml").read_text())[
    "diffbot_base_controller"
]["ros__parameters"]

FUZZ = settings(
    max_examples=100, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture]
)

# Values of every kind YAML can carry, the absurd ones included.
scalars = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(min_value=-(2**70), max_value=2**70),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=12),
    st.sampled_from(["0.3", "-1", ".nan", ".inf", "true", "", "base_link_to_left_wheel", "1e400"]),
)
values = st.recursive(
    scalars,
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=6), inner, max_size=3),
    max_leaves=8,
)


@st.composite
def mutated(draw: st.DrawFn, text: str, words: tuple[str, ...]) -> str:
    """`text` with a few random edits: cut short, a span deleted or duplicated, a token replaced."""
    out = text
    for _ in range(draw(st.integers(1, 3))):
        kind = draw(st.sampled_from(["cut", "delete", "dup", "replace", "insert"]))
        i = draw(st.integers(0, len(out)))
        j = min(len(out), i + draw(st.integers(0, 80)))
        if kind == "cut":
            out = out[:i]
        elif kind == "delete":
            out = out[:i] + out[j:]
        elif kind == "dup":
            out = out[:j] + out[i:j] + out[j:]
        elif kind == "replace":
            new = draw(st.sampled_from(words) | st.text(max_size=8))
            out = out[:i] + new + out[j:]
        else:
            out = out[:i] + draw(st.sampled_from(words)) + out[i:]
    return out


def works_or_project_error(fn: Any, *args: Any, **kw: Any) -> Any:
    """Call fn; a DiffctlError must carry a message. Anything else propagates and fails the test."""
    try:
        return fn(*args, **kw)
    except DiffctlError as e:
        assert str(e).strip(), f"{type(e).__name__} without a message"
        assert "Traceback" not in str(e)
        return None


# ------------------------------------------------------------------------------------------------ launch files

LAUNCH_WORDS = (
    "$(var gui)",
    "$(var nope)",
    "$(find-pkg-share diffctl_demo)",
    "$(find-pkg-share nope)",
    "$(env HOME)",
    "$(",
    ")",
    "'",
    '"',
    "- node:",
    "  pkg: x",
    "exec:",
    "on_exit: shutdown",
    "respawn: maybe",
    "if: ",
    "unless: 1",
    "{",
    "}",
    "[",
    "]",
    ":",
    "\t",
    "\n  ",
    "$(dirname)",
    "$(anon n)",
    "respawn_delay: -1",
    "on_exit:",
    "target: gz_sim",
    "- include: {file: x.yaml}",
    "&a",
    "*a",
    "!!python/x",
)
SUBSTITUTION_NAMES = (
    "var",
    "env",
    "optenv",
    "find-pkg-share",
    "dirname",
    "anon",
    "not",
    "and",
    "or",
    "equals",
    "filename",
    "bogus",
)
subst_text = st.builds(
    lambda name, arg, pre: f"{pre}$({name} {arg})",
    st.sampled_from(SUBSTITUTION_NAMES),
    st.sampled_from(["gui", "rtf", "diffctl_demo", "x y", "", "$(var rtf)"]),
    st.text(max_size=4),
)
LAUNCH_TAGS = (
    "arg",
    "let",
    "node",
    "executable",
    "group",
    "include",
    "on_exit",
    "on_start",
    "on_shutdown",
    "log",
    "set_env",
    "unset_env",
    "timer",
    "set_parameter",
    "push-ros-namespace",
    "bogus",
)
LAUNCH_ATTRS = (
    "name",
    "default",
    "value",
    "pkg",
    "exec",
    "cmd",
    "args",
    "param",
    "on_exit",
    "respawn",
    "respawn_delay",
    "if",
    "unless",
    "target",
    "do",
    "message",
    "period",
    "file",
    "replace",
    "namespace",
    "output",
    "wait_for",
    "choices",
    "description",
    "remap",
    "env",
    "exit_code",
    "bogus",
)
launch_value = st.one_of(values, subst_text, st.sampled_from(["gz_sim", "robot_state_publisher", "true", "5"]))
launch_entity = st.recursive(
    st.dictionaries(
        st.sampled_from(LAUNCH_TAGS),
        st.dictionaries(st.sampled_from(LAUNCH_ATTRS), launch_value, max_size=5),
        min_size=1,
        max_size=1,
    ),
    lambda inner: st.dictionaries(
        st.sampled_from(LAUNCH_TAGS),
        st.dictionaries(st.sampled_from(("do", "children", "name", "target")), st.lists(inner, max_size=3), max_size=2),
        min_size=1,
        max_size=1,
    ),
    max_leaves=6,
)


def _resolve_launch(path: Path) -> None:
    """What `diffctl launch` does before anything starts: read the file and check its arguments. A bad file is
    one error naming the file (its line, for the markup frontends' own errors), nothing else."""
    from diffctl.cli.launch import _check_arguments, _load

    try:
        _check_arguments(_load(path), {}, path)
    except DiffctlError as e:
        assert str(path) in str(e) and "\n" not in str(e).strip(), str(e)
        raise


@FUZZ
@given(text=mutated(LAUNCH_TEXT, LAUNCH_WORDS))
def test_mutated_launch_files_load_or_say_why(text: str, tmp_path: Path) -> None:
    path = tmp_path / "sim_control.yaml"
    path.write_text(text)
    works_or_project_error(_resolve_launch, path)


# ------------------------------------------------------------------------------------------------ launch tests

LAUNCH_TEST_TEXT = (REPO / "tests" / "testing" / "launch_tests" / "params_launch_test.py").read_text()
LAUNCH_TEST_WORDS = (
    "def generate_test_description(x):\n",
    "generate_test_description",
    "launch_testing.actions.ReadyToTest()",
    "@launch_testing.parametrize('thing', [1, 2])\n",
    "@launch_testing.parametrize('nope', [])\n",
    "@unittest.skip('why')\n",
    "return None\n",
    "    return 1, 2\n",
    "yield",
    "raise ValueError('x')",
    "import not_a_module\n",
    "launch.LaunchDescription",
    "self",
    "(",
    ")",
    "[",
    "]",
    ":",
    ",",
    "\n    ",
    "'",
    "=",
)


@FUZZ
@given(text=mutated(LAUNCH_TEST_TEXT, LAUNCH_TEST_WORDS))
def test_mutated_launch_tests_load_or_say_why_in_one_line(text: str, tmp_path: Path) -> None:
    """As `diffctl test` / `launch_test` read a launch test before launching it (import, runs, validation, the
    descriptions): it works, or one LaunchTestError names the file. Nothing is launched."""
    path = tmp_path / f"fuzz_{abs(hash(text))}_launch_test.py"  # a new name: no stale bytecode, no module reuse
    path.write_text(text)
    try:
        _, runs = load_launch_test(path, path.stem)
        describe(path, runs)
    except LaunchTestError as e:
        message = str(e)
        assert message.startswith(str(path)) or message.startswith(f"{path}:"), message
        assert "\n" not in message.strip() and "Traceback" not in message


@FUZZ
@given(doc=st.lists(launch_entity, max_size=4) | values)
def test_generated_launch_documents_load_or_say_why(doc: Any, tmp_path: Path) -> None:
    path = tmp_path / "gen.yaml"
    path.write_text(yaml.safe_dump({"launch": doc} if isinstance(doc, list) else doc))
    works_or_project_error(_resolve_launch, path)


# ------------------------------------------------------------------------------------------------ SDF

SDF_WORDS = (
    "<link>",
    "</link>",
    "<joint name='j' type='revolute'>",
    "</model>",
    "<pose>",
    "</pose>",
    "nan",
    "inf",
    "-1e308",
    "1e999",
    "0 0 0",
    "a b c",
    "<![CDATA[",
    "&amp;",
    "&bogus;",
    "<!DOCTYPE x [<!ENTITY e 'x'>]>",
    "<include><uri>model://nope</uri></include>",
    "<mass>0</mass>",
    "<radius>-1</radius>",
    "<?xml",
    "\x00",
    "<sdf version='9.9'>",
    "<plugin filename='gz_ros2_control-system' name='x'>",
    "<ros2_control name='x' type='system'>",
    "<param name='min'>x</param>",
    "<parent>nope</parent>",
)


@FUZZ
@given(text=mutated(SDF_TEXT, SDF_WORDS))
def test_mutated_robot_descriptions_load_or_say_why(text: str, tmp_path: Path) -> None:
    model = works_or_project_error(parse_model, text, source="robot_description", base_dir=tmp_path)
    if model is not None:
        for link in model.links.values() if isinstance(model.links, dict) else model.links:
            assert all(math.isfinite(v) for v in link.pose_world.xyz), f"link {link.name} at a non-finite pose"
    works_or_project_error(ros2_control_blocks, text)


@FUZZ
@given(text=mutated(WORLD_TEXT, SDF_WORDS))
def test_mutated_worlds_load_or_say_why(text: str, tmp_path: Path) -> None:
    works_or_project_error(parse_world, text, source="empty.world", base_dir=tmp_path)


# ------------------------------------------------------------------------------------------------ bridge config

bridge_entry = st.dictionaries(
    st.sampled_from((*KEYS, "bogus", "ros_type", "direction")),
    st.one_of(
        values,
        st.sampled_from(
            [
                "GZ_TO_ROS",
                "ROS_TO_GZ",
                "BIDIRECTIONAL",
                "/clock",
                "gz.msgs.Clock",
                "rosgraph_msgs/msg/Clock",
                "gz.msgs.Nope",
                "sensor_msgs/msg/Imu",
            ]
        ),
    ),
    max_size=8,
)


@FUZZ
@given(
    doc=st.lists(bridge_entry, max_size=4)
    | values
    | mutated(BRIDGE_TEXT, ("direction: UP", "lazy: 7", "- ", "gz.msgs.Image", "[", "{", ":"))
)
def test_bridge_configs_load_or_say_why(doc: Any, tmp_path: Path) -> None:
    path = tmp_path / "bridge.yaml"
    path.write_text(doc if isinstance(doc, str) else yaml.safe_dump(doc))
    works_or_project_error(load_config, path)


@FUZZ
@given(
    arg=st.text(alphabet=st.sampled_from(list("/@[]abc.:_ ")) | st.characters(), max_size=30)
    | st.builds(
        lambda t, r, d, g: f"{t}@{r}{d}{g}",
        st.sampled_from(["/clock", "", "x y", "/a"]),
        st.sampled_from(["rosgraph_msgs/msg/Clock", "nope/msg/X", ""]),
        st.sampled_from("@[]"),
        st.sampled_from(["gz.msgs.Clock", "gz.msgs.Twist", "", "x@y"]),
    )
)
def test_bridge_command_line_entries_parse_or_say_why(arg: str) -> None:
    works_or_project_error(parse_cli_entry, arg)


# ------------------------------------------------------------------------------------------------ controller parameters

PARAM_KEYS = [
    *sorted(DIFF_PARAMS),
    "linear.x.max_velocity",
    "bogus.key",
    "angular.z.min_acceleration",
    "velocity_rolling_window_size",
]


@FUZZ
@given(
    changes=st.dictionaries(st.sampled_from(PARAM_KEYS), values, min_size=1, max_size=4),
    dropped=st.lists(st.sampled_from(sorted(DIFF_PARAMS)), max_size=2),
)
def test_diff_drive_parameters_validate_or_say_why(changes: dict[str, Any], dropped: list[str]) -> None:
    params = {k: v for k, v in DIFF_PARAMS.items() if k not in dropped} | changes
    result = works_or_project_error(DiffDriveParams.from_params, params, "diffbot_base_controller")
    if result is not None:
        p, _ = result
        # What was accepted is physically meaningful: no NaN/inf or non-positive geometry reaches the physics.
        for v in (
            p.wheel_separation_m,
            p.wheel_radius_m,
            p.effective_wheel_separation_m,
            p.left_wheel_radius_m,
            p.right_wheel_radius_m,
            p.publish_rate_hz,
            p.cmd_vel_timeout_s,
        ):
            assert math.isfinite(v) and v >= 0, (v, changes)
        assert p.wheel_radius_m > 0 and p.wheel_separation_m > 0


# ------------------------------------------------------------------------------------------------ topic pub values

PUB_TYPES = (
    "geometry_msgs/msg/TwistStamped",
    "geometry_msgs/msg/Twist",
    "sensor_msgs/msg/JointState",
    "std_msgs/msg/String",
    "nav_msgs/msg/Odometry",
    "rosgraph_msgs/msg/Clock",
    "std_msgs/msg/UInt8",
    "sensor_msgs/msg/Image",
    "tf2_msgs/msg/TFMessage",
)
FIELD_NAMES = (
    "twist",
    "linear",
    "angular",
    "x",
    "y",
    "z",
    "header",
    "stamp",
    "sec",
    "nanosec",
    "frame_id",
    "data",
    "name",
    "position",
    "velocity",
    "effort",
    "transforms",
    "clock",
    "pose",
    "bogus",
    "height",
    "encoding",
)
pub_values = st.recursive(
    scalars,
    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.sampled_from(FIELD_NAMES), inner, max_size=3),
    max_leaves=10,
)


@settings(FUZZ, max_examples=150)
@given(
    typename=st.sampled_from(PUB_TYPES),
    doc=st.dictionaries(st.sampled_from(FIELD_NAMES), pub_values, max_size=3)
    | st.text(max_size=40)
    | st.sampled_from(
        [
            "{twist: {linear: {x: .nan}}}",
            "{data: [1, 2}",
            "- 1",
            "{header: {stamp: {sec: -1}}}",
            "{data: 300}",
            "{data: 99999999999999999999}",
            "{name: [a, 1]}",
            "{x: 1e400}",
        ]
    ),
)
def test_topic_pub_values_build_a_message_or_say_why(typename: str, doc: Any) -> None:
    text = doc if isinstance(doc, str) else yaml.safe_dump(doc, default_flow_style=True)

    def build() -> Any:
        msg = types.new(typename, parse_values(text))
        # What was accepted goes on the wire and comes back the same.
        raw = types.serialize(msg, typename)
        back = types.to_dict(types.deserialize(raw, typename))
        assert _same(back, types.to_dict(msg)), (back, types.to_dict(msg))
        return msg

    works_or_project_error(build)


def _same(a: Any, b: Any) -> bool:
    """Equality where NaN equals NaN (nested dicts and lists)."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, float) and isinstance(b, float):
        return (math.isnan(a) and math.isnan(b)) or math.isclose(a, b, rel_tol=1e-6)
    return a == b


@settings(FUZZ, max_examples=150)
@given(
    typename=st.sampled_from(PUB_TYPES),
    raw=st.binary(max_size=64) | st.sampled_from([b"", b"\x00\x01\x00\x00", b"\x00\x01\x00\x00" + b"\xff" * 12]),
)
def test_any_payload_decodes_or_is_a_message_error(typename: str, raw: bytes) -> None:
    """What subscriptions do with foreign bytes: a message or MessageError (then: dropped with a warning)."""
    works_or_project_error(types.deserialize, raw, typename)
