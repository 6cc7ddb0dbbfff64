"""launch / launch_ros pieces that were missing, each as ros2/launch and launch_ros (jazzy) define it.

OpaqueCoroutine (`launch/actions/opaque_coroutine.py`: `coroutine(context, *args, **kwargs)` scheduled on the
launch loop, cancelled on shutdown, `ignore_context`), ExecuteLocal / descriptions.Executable
(`launch/actions/execute_local.py`, `launch/descriptions/executable.py`). The supervisor runs on a fake clock
and fake processes (conftest `fake_run`).
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import ClassVar

import pytest

from diffctl.errors import LaunchError
from diffctl.launch_legacy.loader import load
from diffctl.launch_legacy.plan import Unknown, walk
from diffctl.launch_legacy.resolver import resolve


def started(run) -> list[str]:
    return [n for _, n, _ in run.spawner.spawned]


def test_an_opaque_coroutine_runs_on_the_launch_loop_with_its_context(fake_run, tmp_path: Path) -> None:
    out = tmp_path / "seen.txt"
    run = fake_run(
        f"""
import asyncio
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, OpaqueCoroutine

async def watch(context, tag, *, suffix):
    seen = [context.launch_configurations["who"]]
    await asyncio.sleep(0)
    await asyncio.sleep(0.02)
    seen.append(tag + suffix)
    with open({str(out)!r}, "w") as f:
        f.write(" ".join(seen))

def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument("who", default_value="me"),
        OpaqueCoroutine(coroutine=watch, args=["after"], kwargs={{"suffix": "-sleep"}}),
    ])
""",
        suffix=".launch.py",
    )
    assert not run.sup.done  # the launch waits for the pending coroutine, as ROS waits for its future
    for _ in range(200):  # asyncio.sleep keeps real time, the supervisor a fake clock: give it both
        if out.exists():
            break
        time.sleep(0.002)
        run.advance(0.01)
    assert out.read_text() == "me after-sleep"
    run.advance(0.2)
    assert run.sup.done and run.sup.exit_code == 0


def test_an_opaque_coroutine_is_cancelled_on_shutdown_and_ignore_context_drops_it(fake_run, tmp_path: Path) -> None:
    out = tmp_path / "cancelled.txt"
    run = fake_run(
        f"""
import asyncio
from launch import LaunchDescription
from launch.actions import ExecuteProcess, OpaqueCoroutine

async def forever(*args):
    try:
        await asyncio.sleep(3600)
    except asyncio.CancelledError:
        with open({str(out)!r}, "w") as f:
            f.write(f"cancelled with {{len(args)}} args")
        raise

def generate_launch_description():
    return LaunchDescription([
        ExecuteProcess(cmd=["sleep", "100"], name="worker"),
        OpaqueCoroutine(coroutine=forever, ignore_context=True),
    ])
""",
        suffix=".launch.py",
    )
    run.advance(0.1)
    run.spawner.exit("worker", 0)
    run.advance(0.5)
    assert not run.sup.done  # as ROS's LaunchService: not idle while an action's future is pending
    run.sup.shutdown("as a Ctrl-C would")
    run.advance(0.5)
    assert run.sup.done
    assert out.read_text() == "cancelled with 0 args"


def test_an_opaque_coroutine_needs_an_async_function(tmp_path: Path) -> None:
    from diffctl.launch_legacy import OpaqueCoroutine

    with pytest.raises(LaunchError, match="coroutine function"):
        OpaqueCoroutine(coroutine=lambda context: None)


def test_print_says_a_coroutine_is_known_only_at_run_time(tmp_path: Path) -> None:
    path = tmp_path / "co.launch.py"
    path.write_text(
        """
from launch import LaunchDescription
from launch.actions import OpaqueCoroutine

async def later(context):
    raise RuntimeError("must not run under --print")

def generate_launch_description():
    return LaunchDescription([OpaqueCoroutine(coroutine=later)])
"""
    )
    steps = list(walk(resolve(load(path), {}, str(path)).steps))
    assert [s.what for s in steps if isinstance(s, Unknown)] == ["OpaqueCoroutine later"]


def test_execute_local_runs_its_executable_description(fake_run) -> None:
    run = fake_run(
        """
from launch import LaunchDescription
from launch.actions import ExecuteLocal
from launch.descriptions import Executable
from launch.substitutions import LaunchConfiguration

def generate_launch_description():
    return LaunchDescription([
        ExecuteLocal(
            process_description=Executable(
                cmd=["echo", "hi"], name="local", additional_env={"GREETING": "hello"}, arguments=["there"]
            ),
            output="screen",
        ),
    ])
""",
        suffix=".launch.py",
    )
    assert started(run) == ["local"]
    argv = run.spawner.spawned[0][2]
    assert argv[-2:] == ["hi", "there"] and argv[0].endswith("echo")
    assert run.spawner.envs["local"]["GREETING"] == "hello"


def test_execute_local_refuses_a_description_that_is_not_an_executable() -> None:
    from diffctl.launch_legacy import ExecuteLocal

    with pytest.raises(LaunchError, match="Executable"):
        ExecuteLocal(process_description={"cmd": ["true"]})


def test_execute_local_and_executable_are_in_the_ros_modules() -> None:
    import launch.actions
    import launch.descriptions

    assert issubclass(launch.actions.ExecuteLocal, launch.actions.ExecuteProcess)
    assert launch.descriptions.Executable is not None


# ---- OnIncludeLaunchDescription, events.IncludeLaunchDescription, event_named ------------------------------------
# (launch/event_handlers/on_include_launch_description.py, launch/events/include_launch_description.py,
# launch/event_handlers/event_named.py; LaunchService registers one OnIncludeLaunchDescription at start.)

INCLUDE_EVENT = """
from launch import LaunchDescription
from launch.actions import EmitEvent, ExecuteProcess, LogInfo, RegisterEventHandler
from launch.event_handlers import OnIncludeLaunchDescription, event_named
from launch.events import IncludeLaunchDescription
from launch import EventHandler

def generate_launch_description():
    return LaunchDescription([
        RegisterEventHandler(EventHandler(
            matcher=event_named("launch.events.IncludeLaunchDescription"), entities=[LogInfo(msg="saw the include")])),
        RegisterEventHandler(EventHandler(
            matcher=event_named("launch.events.process.ProcessExited"), entities=[LogInfo(msg="saw an exit")])),
        EmitEvent(event=IncludeLaunchDescription(LaunchDescription([
            LogInfo(msg="included"), ExecuteProcess(cmd=["true"], name="from_include")]))),
    ])
"""


def logs(run) -> list[str]:
    return [line.split("]: ", 1)[1] for line in run.text().splitlines() if "]: " in line]


def test_an_emitted_include_event_is_visited_after_the_handlers_registered_later(fake_run) -> None:
    run = fake_run(INCLUDE_EVENT, suffix=".launch.py")
    run.advance(0.1)
    assert logs(run)[:2] == ["saw the include", "included"]
    assert started(run) == ["from_include"]
    run.spawner.exit("from_include", 0)
    run.advance(0.1)
    assert "saw an exit" in logs(run)
    assert run.sup.done and run.sup.exit_code == 0


def test_a_registered_on_include_handler_visits_the_description_again(fake_run) -> None:
    run = fake_run(
        """
from launch import LaunchDescription
from launch.actions import EmitEvent, LogInfo, RegisterEventHandler
from launch.event_handlers import OnIncludeLaunchDescription
from launch.events import IncludeLaunchDescription

def generate_launch_description():
    return LaunchDescription([
        RegisterEventHandler(OnIncludeLaunchDescription()),
        EmitEvent(event=IncludeLaunchDescription(LaunchDescription([LogInfo(msg="included")]))),
    ])
""",
        suffix=".launch.py",
    )
    run.advance(0.1)
    assert logs(run)[:2] == ["included", "included"]  # as ROS: its handler and the launch's own one


def test_event_named_matches_by_ros_type_name() -> None:
    from diffctl.launch_legacy import event_named
    from diffctl.launch_legacy.events import ProcessExited, ProcessIO, Shutdown

    assert event_named("launch.events.Shutdown")(Shutdown())
    assert event_named("launch.events.process.ProcessExited")(ProcessExited(action=None, name="p", pid=1))
    assert event_named("launch.events.process.ProcessStderr")(ProcessIO(action=None, name="p", pid=1, fd=2))
    assert not event_named("launch.events.process.ProcessStdout")(ProcessIO(action=None, name="p", pid=1, fd=2))


# ---- LifecycleTransition (launch_ros/actions/lifecycle_transition.py) -----------------------------------------


class FakeLifecycleNodes:
    """The bus side of managed nodes, as a node answers: each accepted transition publishes two transition
    events (into the intermediate state, then to the goal); `refuse` makes one go to errorprocessing."""

    STEPS: ClassVar[dict[int, tuple[str, str, str]]] = {
        1: ("unconfigured", "configuring", "inactive"),
        3: ("inactive", "activating", "active"),
        4: ("active", "deactivating", "inactive"),
        2: ("inactive", "cleaningup", "unconfigured"),
    }

    def __init__(self, post, refuse: set[int] | None = None) -> None:
        self.post, self.refuse = post, refuse or set()
        self.watchers: dict[str, object] = {}
        self.calls: list[tuple[str, int]] = []

    def watch_transitions(self, node_fqn, on_transition) -> None:
        self.watchers[node_fqn] = on_transition

    def change_state(self, node_fqn, transition_id, done) -> None:
        self.calls.append((node_fqn, transition_id))
        start, middle, goal = self.STEPS[transition_id]
        notify = self.watchers[node_fqn]
        label = {1: "configure", 2: "cleanup", 3: "activate", 4: "deactivate"}[transition_id]
        notify(label, start, middle, None)
        if transition_id in self.refuse:
            notify(label, middle, "errorprocessing", None)
        else:
            notify(label, middle, goal, None)
        self.post(lambda: done(transition_id not in self.refuse, "refused"))


LIFECYCLE = """
from launch import LaunchDescription
from launch.actions import LogInfo, RegisterEventHandler
from launch_ros.actions import LifecycleNode, LifecycleTransition
from launch_ros.event_handlers import OnStateTransition
from lifecycle_msgs.msg import Transition

def generate_launch_description():
    return LaunchDescription([
        LifecycleNode(executable="true", name="a", namespace=""),
        LifecycleNode(executable="true", name="b", namespace="ns"),
        RegisterEventHandler(OnStateTransition(goal_state="active", entities=[LogInfo(msg="an active node")])),
        LifecycleTransition(lifecycle_node_names=["a", "/ns/b"],
                            transition_ids=[Transition.TRANSITION_CONFIGURE, "3"]),
    ])
"""


def _lifecycle_run(fake_run, refuse: set[int] | None = None):
    run = fake_run(LIFECYCLE, suffix=".launch.py", start=False)
    made: list[FakeLifecycleNodes] = []
    run.sup._make_lifecycle = lambda post: made.append(FakeLifecycleNodes(post, refuse)) or made[0]
    run.sup.start()
    run.advance(0.3)
    return run, made[0]


def test_lifecycle_transition_walks_each_named_node_through_its_transitions(fake_run) -> None:
    run, nodes = _lifecycle_run(fake_run)
    assert sorted(nodes.calls) == [("/a", 1), ("/a", 3), ("/ns/b", 1), ("/ns/b", 3)]
    assert nodes.calls.index(("/a", 3)) > nodes.calls.index(("/a", 1))  # the next once the first reached its goal
    assert logs(run).count("an active node") == 2
    # the last transition removed what was left of them (the errorprocessing handlers too)
    assert not any(h.handle_once for h in run.sup.engine.context.handlers)


def test_lifecycle_transition_stops_a_node_whose_transition_fails(fake_run) -> None:
    run, nodes = _lifecycle_run(fake_run, refuse={1})
    assert sorted(nodes.calls) == [("/a", 1), ("/ns/b", 1)]  # no activate after a failed configure
    text = "\n".join(logs(run))
    assert "Stopping transitions for a because 'error occured during transitions'" in text


@pytest.mark.parametrize(
    ("ids", "names", "message"),
    [([], ["a"], "no transition_ids"), ([1], [], "no lifecycle_node_names")],
)
def test_lifecycle_transition_needs_names_and_transitions(ids, names, message) -> None:
    from diffctl.launch_legacy import LifecycleTransition

    with pytest.raises(LaunchError, match=message):
        LifecycleTransition(lifecycle_node_names=names, transition_ids=ids)


def test_lifecycle_transition_ids_are_lifecycle_transitions(fake_run) -> None:
    text = """
from launch import LaunchDescription
from launch_ros.actions import LifecycleTransition

def generate_launch_description():
    return LaunchDescription([LifecycleTransition(lifecycle_node_names=["a"], transition_ids=[ID])])
"""
    with pytest.raises(
        LaunchError, match=r"case0.launch.py:6: LifecycleTransition: expected an integer transition id, got 'activate'"
    ):
        fake_run(text.replace("ID", '"activate"'), suffix=".launch.py")
    with pytest.raises(LaunchError, match="9 is not a lifecycle transition id"):
        fake_run(text.replace("ID", "9"), suffix=".launch.py")


@pytest.mark.slow
def test_lifecycle_transition_drives_a_real_managed_node(router, launch_run) -> None:
    data = Path(__file__).parent / "data" / "lifecycle"
    run = launch_run(str(data / "transition.launch.py"), "--no-router")
    assert run.wait(30) == 0, run.text()
    text = run.text()
    order = ["configuring", "activating", "now active", "shutting down: managed node is active"]
    positions = [text.index(m) for m in order]
    assert positions == sorted(positions), text
    assert run.leftovers() == []


# ---- $(param …) and launch_ros.substitutions.Parameter, $(launch_log_dir) / $(log_dir) ----------------------------
# (launch_ros/substitutions/parameter.py: @expose_substitution('param'), the first `global_params` pair of the
# name as str(value); launch/substitutions/launch_log_dir.py: 'launch_log_dir' and 'log_dir'.)


def test_the_parameter_substitution_reads_what_set_parameter_set(fake_run) -> None:
    # The real Jazzy launch logs exactly this line for this file (run beside it while writing this test).
    run = fake_run(
        """
from launch import LaunchDescription
from launch.actions import LogInfo
from launch_ros.actions import SetParameter
from launch_ros.substitutions import Parameter

def generate_launch_description():
    return LaunchDescription([
        SetParameter(name="x", value="5"),
        SetParameter(name="b", value=True),
        SetParameter(name="s", value="hello"),
        SetParameter(name="f", value=2.5),
        LogInfo(msg=["x=", Parameter("x"), " b=", Parameter("b"), " s=", Parameter("s"), " f=", Parameter("f"),
                     " d=", Parameter("missing", default=7)]),
    ])
""",
        suffix=".launch.py",
    )
    assert logs(run)[0] == "x=5 b=True s=hello f=2.5 d=7"


def test_param_in_xml_and_yaml_with_a_default_and_a_clear_error_when_not_set(fake_run) -> None:
    run = fake_run(
        '<launch>\n  <set_parameter name="x" value="hi"/>\n'
        '  <log message="x=$(param x) y=$(param y fallback)"/>\n</launch>\n',
        suffix=".launch.xml",
    )
    assert logs(run)[0] == "x=hi y=fallback"
    run = fake_run(
        "launch:\n- set_parameter: {name: x, value: yo}\n- log: {message: 'x=$(param x) at $(log_dir)'}\n",
        suffix=".launch.yaml",
    )
    assert logs(run)[0].startswith("x=yo at /")
    with pytest.raises(LaunchError, match="parameter 'nope' not found"):
        fake_run("launch:\n- log: {message: '$(param nope)'}\n", suffix=".launch.yaml")
    with pytest.raises(LaunchError, match=r"\$\(param\) takes 1 or 2 arguments"):
        fake_run("launch:\n- log: {message: '$(param)'}\n", suffix=".launch.yaml")


def test_launch_ros_substitutions_parameter_is_the_substitution() -> None:
    import launch_ros.parameter_descriptions
    import launch_ros.substitutions

    assert launch_ros.substitutions.Parameter is not launch_ros.parameter_descriptions.Parameter
    assert type(launch_ros.substitutions.Parameter("x")).__name__ == "ParameterSubstitution"


# ---- node_container / composable_node tags (launch_ros ComposableNodeContainer.parse, ComposableNode.parse) ------

CONTAINER_XML = """<launch>
  <arg name="second" default="false"/>
  <node_container pkg="rclcpp_components" exec="component_container" name="my_container" namespace="">
    <composable_node pkg="demo" plugin="talker_component:Talker" name="talker1" namespace="ns">
      <param name="greeting" value="hello"/>
      <remap from="chatter" to="talk"/>
      <extra_arg name="use_intra_process_comms" value="true"/>
    </composable_node>
    <composable_node pkg="demo" plugin="talker_component:Talker" name="talker2" if="$(var second)"/>
  </node_container>
</launch>
"""

CONTAINER_YAML = """launch:
- arg: {name: second, default: "false"}
- node_container:
    pkg: rclcpp_components
    exec: component_container
    name: my_container
    namespace: ""
    composable_node:
    - pkg: demo
      plugin: talker_component:Talker
      name: talker1
      namespace: ns
      param: [{name: greeting, value: hello}]
      remap: [{from: chatter, to: talk}]
      extra_arg: [{name: use_intra_process_comms, value: "true"}]
    - {pkg: demo, plugin: "talker_component:Talker", name: talker2, if: $(var second)}
"""

CONTAINER_PY = """
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import ComposableNodeContainer
from launch_ros.descriptions import ComposableNode

def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument("second", default_value="false"),
        ComposableNodeContainer(
            name="my_container", namespace="", package="rclcpp_components", executable="component_container",
            composable_node_descriptions=[
                ComposableNode(package="demo", plugin="talker_component:Talker", name="talker1", namespace="ns",
                               parameters=[{"greeting": "hello"}], remappings=[("chatter", "talk")],
                               extra_arguments=[{"use_intra_process_comms": True}]),
                ComposableNode(package="demo", plugin="talker_component:Talker", name="talker2",
                               condition=IfCondition(LaunchConfiguration("second"))),
            ]),
    ])
"""


def _container_nodes(tmp_path: Path, name: str, text: str, arguments: dict[str, str]) -> list[dict]:
    import json

    from diffctl.launch_legacy.plan import StartProcess

    path = tmp_path / name
    path.write_text(text)
    starts = [s for s in walk(resolve(load(path), arguments, str(path)).steps) if isinstance(s, StartProcess)]
    argv = list(starts[0].spec.argv)
    return json.loads(argv[argv.index("--nodes") + 1])


@pytest.mark.parametrize("second", ["false", "true"])
def test_node_container_tags_load_the_same_nodes_as_the_python_container(tmp_path: Path, second: str) -> None:
    args = {"second": second}
    python = _container_nodes(tmp_path, "c.launch.py", CONTAINER_PY, args)
    assert [n["cli_args"][2] for n in python] == ["__node:=talker1", "__node:=talker2"][: 1 + (second == "true")]
    assert "chatter:=talk" in python[0]["cli_args"] and "greeting:=hello" in python[0]["cli_args"]
    assert _container_nodes(tmp_path, "c.launch.xml", CONTAINER_XML, args) == python
    assert _container_nodes(tmp_path, "c.launch.yaml", CONTAINER_YAML, args) == python


def test_a_composable_node_needs_its_plugin(tmp_path: Path) -> None:
    bad = CONTAINER_XML.replace(' plugin="talker_component:Talker" name="talker2"', ' name="talker2"')
    with pytest.raises(LaunchError, match="plugin"):
        _container_nodes(tmp_path, "bad.launch.xml", bad, {})


def test_load_composable_node_names_its_container_by_text(tmp_path: Path) -> None:
    load_tag = (
        '  <load_composable_node target="TARGET">\n'
        '    <composable_node pkg="demo" plugin="talker_component:Talker" name="talker3"/>\n'
        "  </load_composable_node>\n</launch>\n"
    )
    text = CONTAINER_XML.replace("</launch>\n", load_tag)
    nodes = _container_nodes(tmp_path, "l.launch.xml", text.replace("TARGET", "my_container"), {})
    assert [n["cli_args"][2] for n in nodes] == ["__node:=talker1", "__node:=talker3"]
    assert _container_nodes(tmp_path, "l2.launch.xml", text.replace("TARGET", "/my_container"), {}) == nodes
    with pytest.raises(LaunchError, match="no container '/elsewhere' in this launch"):
        _container_nodes(tmp_path, "l3.launch.xml", text.replace("TARGET", "elsewhere"), {})


def test_an_opaque_coroutine_that_raises_fails_the_launch_a_listed_difference(fake_run) -> None:
    run = fake_run(
        """
from launch import LaunchDescription
from launch.actions import ExecuteProcess, OpaqueCoroutine

async def broken(context):
    raise RuntimeError("no luck")

def generate_launch_description():
    return LaunchDescription([ExecuteProcess(cmd=["sleep", "100"], name="worker"), OpaqueCoroutine(coroutine=broken)])
""",
        suffix=".launch.py",
    )
    run.advance(0.5)
    assert run.sup.done and run.sup.exit_code == 1
    assert any("OpaqueCoroutine broken raised RuntimeError: no luck" in line for line in logs(run))


def test_print_of_a_lifecycle_transition_shows_its_handlers_and_runs_nothing(tmp_path: Path) -> None:
    path = tmp_path / "lt.launch.py"
    path.write_text(LIFECYCLE)
    steps = list(walk(resolve(load(path), {}, str(path)).steps))
    assert not [s for s in steps if isinstance(s, Unknown)]
    handlers = [s for s in steps if type(s).__name__ == "AddHandler"]
    assert len(handlers) == 1 + 2 * 2 + 2  # the file's own, one per node and transition, one per node on error


def test_print_shows_what_an_emitted_include_event_starts(tmp_path: Path) -> None:
    from diffctl.launch_legacy.plan import StartProcess

    path = tmp_path / "inc.launch.py"
    path.write_text(INCLUDE_EVENT)
    steps = list(walk(resolve(load(path), {}, str(path)).steps))
    assert [s.spec.name for s in steps if isinstance(s, StartProcess)] == ["from_include"]
