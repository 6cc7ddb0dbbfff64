"""Launch descriptions: substitutions, frontends, the package index, and every kind of bad input."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from diffctl.errors import LaunchError
from diffctl.launch.context import Scope
from diffctl.launch.loader import load
from diffctl.launch.plan import AddHandler, StartProcess
from diffctl.launch.resolver import resolve
from diffctl.launch.substitutions import parse, perform
from diffctl.workspace import package_index

REPO = Path(__file__).resolve().parents[2]


def plan_of(tmp_path: Path, text: str, arguments: dict[str, str] | None = None, name: str = "t.yaml"):
    path = tmp_path / name
    path.write_text(text)
    return resolve(load(path), arguments or {}, str(path))


def error_of(tmp_path: Path, text: str, name: str = "t.yaml", **kw) -> LaunchError:
    with pytest.raises(LaunchError) as info:
        plan_of(tmp_path, text, name=name, **kw)
    return info.value


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("plain $ text", "plain $ text"),
        ("$(var robot)_ns", "diffbot_ns"),
        ("$(var missing 'fallback value')", "fallback value"),
        ("$(env DIFFCTL_T_SET)/$(optenv DIFFCTL_T_UNSET)|$(optenv DIFFCTL_T_UNSET dflt)", "yes/|dflt"),
        ("$(eval '$(var count) * 2 + 1')", "7"),
        ("$(eval math.pi > 3)", "True"),
        ("$(find-pkg-share diffctl_demo_description)", str(REPO / "description")),
        ("$(dirname)", "/some/dir"),
        ("$(anon talker) == $(anon talker)", None),
        ("$(command 'echo hello')", "hello\n"),
        (r"\$(var robot)", "$(var robot)"),
    ],
)
def test_substitutions_evaluate_as_ros_does(text: str, expected: str | None, monkeypatch) -> None:
    monkeypatch.setenv("DIFFCTL_T_SET", "yes")
    monkeypatch.delenv("DIFFCTL_T_UNSET", raising=False)
    scope = Scope.initial({"robot": "diffbot", "count": "3"}, "/some/dir/x.yaml")
    value = perform(parse(text), scope)
    if expected is None:
        left, right = value.split(" == ")
        assert left == right and left.startswith("talker_")
    else:
        assert value == expected


def test_file_content_replaces_placeholders_declared_in_the_launch_file(tmp_path: Path) -> None:
    (tmp_path / "robot.sdf").write_text("<plugin><parameters>PLACEHOLDER</parameters></plugin>")
    plan = plan_of(
        tmp_path,
        """
launch:
- let:
    name: description
    file: $(dirname)/robot.sdf
    replace: {PLACEHOLDER: $(find-pkg-share diffctl_demo)/config/diff_drive_controller.yaml}
- node:
    pkg: robot_state_publisher
    exec: robot_state_publisher
    param: [{name: robot_description, value: $(var description)}, {name: rate, value: "$(eval 10 * 5)"},
            {name: use_sim_time, value: "true"}, {name: frame, value: base_link}]
""",
    )
    params = plan.processes["robot_state_publisher"].node.params[0]
    assert params["robot_description"] == (
        f"<plugin><parameters>{REPO}/config/diff_drive_controller.yaml</parameters></plugin>"
    )
    assert params["rate"] == 50  # a substituted value is typed as ROS types it
    # launch_yaml hands a string to launch_ros as a substitution, typed by YAML rules: "true" is a boolean (the
    # secured two-host test's robot_state_publisher refused the text 'true' for its bool use_sim_time)
    assert (params["use_sim_time"], params["frame"]) == (True, "base_link")


def test_groups_scope_configurations_namespaces_and_environment(tmp_path: Path) -> None:
    plan = plan_of(
        tmp_path,
        """
launch:
- let: {name: who, value: outer}
- group:
    namespace: robot1
    children:
    - let: {name: who, value: inner}
    - set_env: {name: DIFFCTL_T_GROUP, value: "1"}
    - node: {pkg: robot_state_publisher, exec: robot_state_publisher, name: "$(var who)"}
- group:
  - push_ros_namespace: {namespace: /abs}
  - node: {pkg: robot_state_publisher, exec: robot_state_publisher, name: "$(var who)", namespace: sub}
""",
    )
    inner, outer = plan.processes["inner"], plan.processes["outer"]
    assert (inner.node.namespace, inner.env) == ("/robot1", {"DIFFCTL_T_GROUP": "1"})
    assert (outer.node.namespace, outer.env) == ("/abs/sub", {})


def test_include_passes_arguments_and_is_not_scoped_as_in_jazzy(tmp_path: Path) -> None:
    (tmp_path / "inner.yaml").write_text("""
launch:
- arg: {name: exe}
- let: {name: leaked, value: "yes"}
- executable: {cmd: "$(var exe) 10", name: inner}
""")
    plan = plan_of(
        tmp_path,
        """
launch:
- include: {file: $(dirname)/inner.yaml, arg: [{name: exe, value: sleep}]}
- executable: {cmd: "sleep $(var leaked 'no') $(var exe)", name: outer}
- group:
    children:
    - include: {file: $(dirname)/inner.yaml, arg: [{name: exe, value: sleep}, {name: leaked, value: scoped}]}
- executable: {cmd: "sleep $(var leaked 'no')", name: after_group}
""",
    )
    assert plan.processes["inner"].argv == ("sleep", "10")
    # Jazzy's IncludeLaunchDescription is not scoped: the child's `let` and the passed argument stay set.
    assert plan.processes["outer"].argv == ("sleep", "yes", "sleep")
    # A (scoped) group around an include keeps them inside.
    assert plan.processes["after_group"].argv == ("sleep", "yes")


def test_python_and_yaml_launch_files_include_each_other(tmp_path: Path) -> None:
    (tmp_path / "inner.launch.py").write_text("""
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, ExecuteProcess
from launch.substitutions import LaunchConfiguration

def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument("seconds", default_value="5"),
        ExecuteProcess(cmd=["sleep", LaunchConfiguration("seconds")], name="py_inner"),
    ])
""")
    plan = plan_of(
        tmp_path,
        """
launch:
- include: {file: inner.launch.py, arg: [{name: seconds, value: "7"}]}
""",
    )
    assert plan.processes["py_inner"].argv == ("sleep", "7")


def test_the_package_index_maps_ros_names_to_diffctl_components() -> None:
    argv = package_index.executable_argv("controller_manager", "ros2_control_node")
    assert argv == [sys.executable, "-m", "diffctl", "control", "manager"]
    assert package_index.executable_argv("ros_gz_bridge", "parameter_bridge")[-1] == "bridge"
    assert package_index.share_dir("diffctl_demo") == REPO
    assert package_index.find_launch_file("teleop") == REPO / "launch" / "teleop.yaml"


def test_the_project_packages_resolve_from_an_installed_wheel_layout(tmp_path: Path, monkeypatch) -> None:
    share = tmp_path / "share"
    (share / "launch").mkdir(parents=True)
    (share / "description").mkdir()
    (share / "launch" / "demo.launch.py").write_text("")
    monkeypatch.setenv("DIFFCTL_PROJECT_DIR", str(share))
    assert package_index.share_dir("diffctl_demo_description") == share / "description"
    assert package_index.find_launch_file("demo", cwd=tmp_path) == share / "launch" / "demo.launch.py"
    assert package_index.find_launch_file("diffctl_demo", "demo.launch.py") == share / "launch" / "demo.launch.py"


def test_python_event_handlers_target_the_action_objects(tmp_path: Path) -> None:
    plan = resolve(
        load(REPO / "tests/launch/data/chain.launch.py"),
        {"record": "-"},
        str(REPO / "tests/launch/data/chain.launch.py"),
    )
    handlers = [s.handler for s in plan.steps if isinstance(s, AddHandler)]
    assert [(h.event, [t.name for t in h.targets]) for h in handlers] == [
        ("exit", ["base_spawner"]),
        ("exit", ["jsb_spawner"]),
        ("start", ["viz"]),
    ]
    assert [s.spec.name for s in handlers[0].steps if isinstance(s, StartProcess)] == ["jsb_spawner"]


BAD_YAML = [
    ("launch:\n- node: {pkg: a, exec: b\n", r"t\.yaml:3:1: malformed YAML"),
    ("launch:\n- nodes: {pkg: rviz2, exec: rviz2}\n", r"t\.yaml:2:3: unknown tag 'nodes' \(did you mean 'node'\?\)"),
    (
        "launch:\n- node:\n    pkg: rviz2\n    exe: rviz2\n",
        r"t\.yaml:4:5: unknown attribute 'exe' of `node` \(did you mean 'exec'",
    ),
    (
        'launch:\n- executable: {cmd: "echo $(vra x)"}\n',
        r"t\.yaml:2:21: executable\.cmd: unknown substitution \$\(vra\) \(did you mean 'var'\?\)",
    ),
    (
        "launch:\n- node: {pkg: rviz, exec: rviz2}\n",
        r"t\.yaml:2:3: node rviz/rviz2: unknown package 'rviz' \(did you mean 'rviz2'\?\) \(rviz is the old name",
    ),
    (
        "launch:\n- node: {pkg: controller_manager, exec: spawnr}\n",
        r"no executable 'spawnr' \(did you mean 'spawner'\?\).*its executables: ros2_control_node, spawner",
    ),
    (
        "launch:\n- executable: {cmd: sleep 1, name: a, respawn_delay: -1}\n",
        r"t\.yaml:2:3: executable a: respawn_delay '-1' must be a finite number of seconds ≥ 0",
    ),
    (
        "launch:\n- executable: {cmd: sleep 1, output: loud}\n",
        r"output 'loud' is not valid \(valid: screen, log, both\)",
    ),
    ("launch:\n- executable: {cmd: no-such-program-here}\n", r"executable 'no-such-program-here' not found on PATH"),
    (
        "launch:\n- executable: {cmd: sleep 1, name: a}\n- on_exit: {target: b, do: []}\n",
        r"t\.yaml:3:3: on_exit: unknown process 'b'.*processes: a",
    ),
    ("launch:\n- executable: {cmd: sleep 1, wait_for: [{exited: ghost}]}\n", r"unknown process 'ghost'"),
    (
        "launch:\n- executable: {cmd: sleep 1, wait_for: [{exits: a}]}\n",
        r"t\.yaml:2:40: executable\.wait_for: unknown wait_for condition 'exits' \(did you mean 'exited'\?\)",
    ),
    ("launch:\n- include: {file: nowhere.yaml}\n", r"included launch file .*nowhere\.yaml does not exist"),
    ("launch:\n- executable: {cmd: sleep 1, if: maybe}\n", r"if maybe: 'maybe' is not a boolean \(valid: true, false"),
    (
        "launch:\n- node:\n    param:\n    - {name: a, value: b}:\n",
        r"t\.yaml:4:7: a mapping key must be a plain name or value, not a mapping or list",
    ),
]


@pytest.mark.parametrize(("text", "pattern"), BAD_YAML)
def test_bad_yaml_is_one_clear_located_message(tmp_path: Path, text: str, pattern: str) -> None:
    import re

    message = str(error_of(tmp_path, text))
    assert "\n" not in message
    assert re.search(pattern, message), message


def test_a_missing_required_argument_lists_the_declared_ones(tmp_path: Path) -> None:
    message = str(
        error_of(
            tmp_path,
            """
launch:
- arg: {name: world, default: empty}
- arg: {name: robot}
- arg: {name: gui, default: "false"}
""",
        )
    )
    assert "t.yaml:4:3: arg robot: missing required launch argument 'robot'" in message
    assert "pass robot:=VALUE; declared arguments: world, robot, gui" in message
    assert str(error_of(tmp_path, "launch:\n- arg: {name: m, choices: [a, b]}\n", arguments={"m": "c"})).endswith(
        "argument 'm' is 'c', not one of its choices (valid: a, b)"
    )


def test_an_include_cycle_is_named(tmp_path: Path) -> None:
    (tmp_path / "b.yaml").write_text("launch:\n- include: {file: $(dirname)/t.yaml}\n")
    message = str(error_of(tmp_path, "launch:\n- include: {file: $(dirname)/b.yaml}\n"))
    assert "include cycle: t.yaml → b.yaml → t.yaml" in message


def test_a_python_launch_file_that_raises_is_one_message_with_its_line(tmp_path: Path) -> None:
    raising = "def generate_launch_description():\n    x = 1\n    return {}['robot']\n"
    bad_kwarg = (
        "from launch_ros.actions import Node\ndef generate_launch_description():\n"
        "    return Node(packge='rviz2', executable='rviz2')\n"
    )
    cases = {
        raising: "raises.launch.py:3: launch file raised KeyError: 'robot'",
        bad_kwarg: "raises.launch.py:3: Node() has no argument 'packge' (did you mean 'package'?)",
        "def generate_launch_description(:\n": "raises.launch.py:1:33: syntax error",
        "x = 1\n": "raises.launch.py: defines no generate_launch_description()",
    }
    for source, expected in cases.items():
        assert expected in str(error_of(tmp_path, source, name="raises.launch.py")), source
    # `launch` is the overlay's module, a real one that stays importable (by an OpaqueFunction called later)
    assert "diffctl/overlay/launch_ros" in sys.modules["launch_ros.actions"].__file__


def test_override_launch_process_output(tmp_path: Path, monkeypatch) -> None:
    monkeypatch.setitem(os.environ, "OVERRIDE_LAUNCH_PROCESS_OUTPUT", "log")
    plan = plan_of(tmp_path, "launch:\n- executable: {cmd: sleep 1, output: screen}\n")
    assert plan.processes["sleep"].output == "log"


def test_yaml_arguments_split_like_a_shell_or_item_by_item(tmp_path: Path) -> None:
    plan = plan_of(
        tmp_path,
        """
launch:
- executable: {cmd: "echo 'two words' $(var x)", name: split}
- executable: {cmd: [echo, two words, "$(var x)"], name: items}
- node: {pkg: rviz2, exec: rviz2, args: [-d, /path with space/x.rviz]}
""",
        {"x": "three"},
    )
    assert plan.processes["split"].argv == plan.processes["items"].argv == ("echo", "two words", "three")
    assert plan.processes["rviz2"].argv[-2:] == ("-d", "/path with space/x.rviz")


@settings(max_examples=150, deadline=None)
@given(st.text(alphabet=st.sampled_from(list("$()'\" \\abvr-x")) | st.characters(), max_size=40))
def test_the_substitution_parser_never_fails_but_with_a_launch_error(text: str) -> None:
    assume("command" not in text and "eval" not in text)  # no running of random programs or expressions
    scope = Scope.initial({"a": "1", "x": "2", "var": "3"}, "/d/f.yaml", env={})
    try:
        value = perform(parse(text), scope)
    except LaunchError as e:
        assert "\n" not in str(e)
        return
    if "$(" not in text:
        assert value == text
