"""The engine behaves as ROS 2 Jazzy's launch does, case by case.

Each expectation is written from ros2/launch and ros2/launch_ros (jazzy branches): `LaunchService.
__process_event` (every matching handler runs, newest registered first), `LaunchContext.register_event_handler`
(prepends), `TimerAction.execute/_wait_to_fire_event` (period and actions evaluated when it fires, with the
launch configurations of that moment), `IncludeLaunchDescription.execute` (not scoped: returns
`SetLaunchConfiguration`s and the description), `GroupAction.execute` (Push/Pop around the actions),
`LaunchService._shutdown` (idle and Ctrl-C set `is_shutdown` before the Shutdown event, so processes of
OnShutdown handlers are skipped; a `Shutdown()` action does not), launch_ros `SetParameter` (`-p`),
`PythonExpression.perform` (empty globals), launch_yaml's `arg` (`choice: [{value: …}]`).
The supervisor runs on a fake clock and fake processes (conftest `fake_run`), so each case is exact.
"""

from __future__ import annotations

import signal
from pathlib import Path

import pytest

from diffctl.errors import LaunchError
from diffctl.launch_legacy import commandline
from diffctl.launch_legacy.loader import load
from diffctl.launch_legacy.plan import StartProcess, Unknown, walk
from diffctl.launch_legacy.resolver import resolve

IMPORTS = """
import os
from launch import LaunchDescription
from launch.actions import (DeclareLaunchArgument, EmitEvent, ExecuteProcess, GroupAction, IncludeLaunchDescription,
    LogInfo, OpaqueFunction, RegisterEventHandler, SetEnvironmentVariable, SetLaunchConfiguration, Shutdown,
    TimerAction, UnsetLaunchConfiguration)
from launch.event_handlers import OnExecutionComplete, OnProcessExit, OnProcessIO, OnProcessStart, OnShutdown
from launch.substitutions import EnvironmentVariable, LaunchConfiguration, PythonExpression, ThisLaunchFileDir
from launch.launch_description_sources import PythonLaunchDescriptionSource
"""


def logs(run) -> list[str]:
    return [line.split("]: ", 1)[1] for line in run.text().splitlines() if "]: " in line]


def started(run) -> list[str]:
    return [n for _, n, _ in run.spawner.spawned]


def test_an_on_exit_function_reads_the_file_the_exited_process_wrote(fake_run, tmp_path: Path) -> None:
    out = tmp_path / "written.txt"
    run = fake_run(
        IMPORTS
        + f"""
def read(context):
    return [LogInfo(msg="read " + open({str(out)!r}).read())]

def generate_launch_description():
    writer = ExecuteProcess(cmd=["true"], name="writer")
    return LaunchDescription([
        writer,
        RegisterEventHandler(OnProcessExit(target_action=writer, on_exit=[OpaqueFunction(function=read)])),
    ])
""",
        suffix=".launch.py",
    )
    assert not out.exists()
    out.write_text("by the writer")  # as the process would before it exits
    run.spawner.exit("writer", 0)
    assert "read by the writer" in logs(run)
    assert run.sup.done and run.sup.exit_code == 0


def test_print_says_what_it_cannot_know_before_run_time(tmp_path: Path) -> None:
    path = tmp_path / "later.launch.py"
    path.write_text(
        IMPORTS
        + """
def read(context):
    return [LogInfo(msg=open("/nonexistent/written-by-a-process").read())]

def generate_launch_description():
    writer = ExecuteProcess(cmd=["true"], name="writer")
    return LaunchDescription([
        writer,
        RegisterEventHandler(OnProcessExit(target_action=writer, on_exit=[OpaqueFunction(function=read)])),
    ])
"""
    )
    plan = resolve(load(path), {}, str(path))  # no FileNotFoundError: the handler is only previewed
    (unknown,) = [s for s in walk(plan.steps) if isinstance(s, Unknown)]
    assert "No such file" in unknown.why
    from diffctl.launch_legacy.render import PlanView

    text = "\n".join(str(line) for line in PlanView(plan).lines())
    assert "on exit of writer (evaluated when it fires; as of now:)" in text
    assert "known only when it runs:" in text and "OpaqueFunction read" in text and "No such file" in text


def test_configurations_and_environment_set_at_event_time_are_seen_by_later_handlers_and_timers(fake_run) -> None:
    run = fake_run(
        IMPORTS
        + """
def generate_launch_description():
    first = ExecuteProcess(cmd=["true"], name="first")
    return LaunchDescription([
        first,
        RegisterEventHandler(OnProcessExit(target_action=first, on_exit=[
            SetLaunchConfiguration("stage", "two"),
            SetEnvironmentVariable("STAGE_ENV", "from-handler"),
        ])),
        TimerAction(period=1.0, actions=[
            LogInfo(msg=["timer sees ", LaunchConfiguration("stage", default="one")]),
            LogInfo(msg=["timer env ", EnvironmentVariable("STAGE_ENV", default_value="unset")]),
            ExecuteProcess(cmd=["sleep", LaunchConfiguration("stage")], name="second"),
        ]),
    ])
""",
        suffix=".launch.py",
    )
    run.advance(0.5)
    run.spawner.exit("first", 0)
    run.advance(0.6)
    assert "timer sees two" in logs(run) and "timer env from-handler" in logs(run)
    assert run.spawner.spawned[-1][1:] == ("second", ["sleep", "two"])
    assert run.spawner.envs["second"]["STAGE_ENV"] == "from-handler"


def test_every_matching_handler_runs_newest_registered_first(fake_run) -> None:
    run = fake_run(
        IMPORTS
        + """
def generate_launch_description():
    p = ExecuteProcess(cmd=["true"], name="p")
    return LaunchDescription([
        p,
        RegisterEventHandler(OnProcessExit(target_action=p, on_exit=[LogInfo(msg="exit A")])),
        RegisterEventHandler(OnProcessExit(on_exit=[LogInfo(msg="exit B (any process)")])),
        RegisterEventHandler(OnShutdown(on_shutdown=[LogInfo(msg="shutdown A")])),
        RegisterEventHandler(OnShutdown(on_shutdown=[LogInfo(msg="shutdown B")])),
    ])
""",
        suffix=".launch.py",
    )
    run.spawner.exit("p", 0)
    got = [m for m in logs(run) if m.startswith(("exit", "shutdown "))]
    assert got == ["exit B (any process)", "exit A", "shutdown B", "shutdown A"]


def test_on_shutdown_processes_start_after_a_shutdown_action_and_are_waited_for(fake_run) -> None:
    body = """
def generate_launch_description():
    return LaunchDescription([
        ExecuteProcess(cmd=["sleep", "100"], name="worker"),
        RegisterEventHandler(OnShutdown(on_shutdown=[ExecuteProcess(cmd=["sleep", "1"], name="cleanup")])),
        TimerAction(period=1.0, actions=[Shutdown(reason="done")]),
    ])
"""
    run = fake_run(IMPORTS + body, suffix=".launch.py")
    run.advance(1.1)
    assert started(run) == ["worker", "cleanup"]
    assert [s[1:] for s in run.spawner.signals] == [("worker", "SIGINT")]  # the Shutdown event predates cleanup
    run.advance(0.1)
    assert not run.sup.done  # launch waits for it
    run.spawner.exit("cleanup", 0)
    assert run.sup.done and run.sup.exit_code == 0

    # Ctrl-C: the context is shutting down before the event is handled, so cleanup never starts.
    run = fake_run(IMPORTS + body, suffix=".launch.py")
    run.sup.on_signal(signal.SIGINT)
    run.advance(0.1)
    assert started(run) == ["worker"] and run.sup.done


def test_on_shutdown_processes_are_skipped_when_the_launch_ends_idle(fake_run) -> None:
    run = fake_run(
        IMPORTS
        + """
def generate_launch_description():
    return LaunchDescription([
        ExecuteProcess(cmd=["true"], name="once"),
        RegisterEventHandler(OnShutdown(on_shutdown=[LogInfo(msg="bye"), ExecuteProcess(cmd=["true"], name="x")])),
    ])
""",
        suffix=".launch.py",
    )
    run.spawner.exit("once", 0)
    assert run.sup.done and started(run) == ["once"] and "bye" in logs(run)


def test_on_execution_complete_of_an_action_and_of_a_process(fake_run) -> None:
    run = fake_run(
        IMPORTS
        + """
def generate_launch_description():
    note = LogInfo(msg="note")
    proc = ExecuteProcess(cmd=["true"], name="proc", respawn=True, respawn_max_retries=1)
    return LaunchDescription([
        RegisterEventHandler(OnExecutionComplete(target_action=note, on_completion=[LogInfo(msg="note done")])),
        RegisterEventHandler(OnExecutionComplete(target_action=proc, on_completion=[LogInfo(msg="proc done")])),
        note,
        proc,
    ])
""",
        suffix=".launch.py",
    )
    assert logs(run).index("note") < logs(run).index("note done")
    run.spawner.exit("proc", 0)
    run.advance(0.1)
    assert "proc done" not in logs(run)  # respawned: not complete yet
    run.spawner.exit("proc", 0)
    assert logs(run).count("proc done") == 1


def test_process_io_handlers_run_in_registration_order_around_the_processes_own_output(fake_run) -> None:
    run = fake_run(
        IMPORTS
        + """
def generate_launch_description():
    talker = ExecuteProcess(cmd=["sleep", "9"], name="talker", output="screen")
    return LaunchDescription([
        RegisterEventHandler(OnProcessIO(target_action=talker, on_stdout=lambda e: [LogInfo(msg="older saw")])),
        talker,
        RegisterEventHandler(OnProcessIO(target_action=talker, on_stdout=lambda e: [LogInfo(msg="newer saw")])),
    ])
""",
        suffix=".launch.py",
    )
    run.sup.on_line("talker", "stdout", "hello")
    lines = [line for line in run.text().splitlines() if "saw" in line or "hello" in line]
    assert ["newer saw" in lines[0], "hello" in lines[1], "older saw" in lines[2]] == [True, True, True]


def test_a_timers_period_and_actions_are_evaluated_after_its_group_is_gone(fake_run) -> None:
    run = fake_run(
        IMPORTS
        + """
def generate_launch_description():
    return LaunchDescription([
        ExecuteProcess(cmd=["sleep", "100"], name="keepalive"),
        GroupAction([
            SetLaunchConfiguration("period", "1"),
            SetLaunchConfiguration("inner", "set in the group"),
            TimerAction(period=LaunchConfiguration("period", default="3"),
                        actions=[LogInfo(msg=["fired: ", LaunchConfiguration("inner", default="gone")])]),
        ]),
    ])
""",
        suffix=".launch.py",
    )
    run.advance(2.0)
    assert not any(m.startswith("fired") for m in logs(run))  # not after 1 s: `period` was popped with the group
    run.advance(1.1)
    assert "fired: gone" in logs(run)


def test_includes_are_not_scoped_in_python_xml_and_yaml(tmp_path: Path) -> None:
    child_dir = tmp_path / "child"
    child_dir.mkdir()
    (child_dir / "child.launch.py").write_text(
        IMPORTS
        + """
def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument("child_arg", default_value="from child"),
        SetLaunchConfiguration("child_set", "set by child"),
        SetEnvironmentVariable("CHILD_ENV", "yes"),
    ])
"""
    )
    (child_dir / "child.launch.xml").write_text(
        '<launch><arg name="child_arg" default="from child"/><let name="child_set" value="set by child"/></launch>'
    )
    (child_dir / "child.launch.yaml").write_text(
        "launch:\n- arg: {name: child_arg, default: from child}\n- let: {name: child_set, value: set by child}\n"
    )
    for name in ("child.launch.py", "child.launch.xml", "child.launch.yaml"):
        parent = tmp_path / f"parent_{name.split('.')[-1]}.launch.yaml"
        parent.write_text(f"""
launch:
- include: {{file: {child_dir / name}, arg: [{{name: passed, value: given}}]}}
- log: {{message: "$(var passed) / $(var child_arg) / $(var child_set) / $(dirname)"}}
- group:
    children:
    - include: {{file: {child_dir / name}, arg: [{{name: scoped, value: x}}]}}
- log: {{message: "$(var scoped 'not leaked')"}}
""")
        plan = resolve(load(parent), {}, str(parent))
        messages = [s.message for s in plan.steps if hasattr(s, "message")]
        # `$(dirname)` after an include names the included file's directory, as ROS's locals do.
        assert messages == [f"given / from child / set by child / {child_dir}", "not leaked"], name


def test_an_included_files_required_argument_must_be_passed_by_the_include(tmp_path: Path) -> None:
    (tmp_path / "child.launch.yaml").write_text("launch:\n- arg: {name: req, description: needed}\n")
    parent = tmp_path / "parent.launch.yaml"
    parent.write_text(
        f"launch:\n- let: {{name: req, value: x}}\n- include: {{file: {tmp_path / 'child.launch.yaml'}}}\n"
    )
    with pytest.raises(LaunchError, match="Included launch description missing required argument 'req'"):
        resolve(load(parent), {}, str(parent))


def test_group_forwarding_false_and_set_parameter_scoping_as_launch_ros(tmp_path: Path) -> None:
    path = tmp_path / "g.launch.xml"
    path.write_text("""
<launch>
  <let name="outer" value="o"/>
  <set_parameter name="before" value="1"/>
  <group scoped="true" forwarding="false">
    <keep name="kept" value="k"/>
    <log message="$(var outer 'hidden') $(var kept)"/>
  </group>
  <group>
    <set_parameter name="inside" value="2"/>
    <set_remap from="a" to="b"/>
  </group>
  <node pkg="robot_state_publisher" exec="robot_state_publisher" name="n"/>
</launch>
""")
    plan = resolve(load(path), {}, str(path))
    assert [s.message for s in plan.steps if hasattr(s, "message")] == ["hidden k"]
    (node,) = [s.spec for s in plan.steps if isinstance(s, StartProcess)]
    # Jazzy's GroupAction copies launch configurations shallowly: `global_params` existed before the group,
    # so the parameter set inside it reaches the node after it; `ros_remaps` did not, so the remap does not.
    assert node.node.global_params == (("before", "1"), ("inside", "2")) and node.node.remaps == ()
    assert commandline.argv(node)[-5:] == ["__node:=n", "-p", "before:=1", "-p", "inside:=2"]


def test_yaml_arg_choice_syntax_and_python_expression_builtins(tmp_path: Path) -> None:
    path = tmp_path / "c.launch.yaml"
    path.write_text("""
launch:
- arg: {name: mode, default: a, choice: [{value: a}, {value: b}]}
- log: {message: "$(eval 'format(sum(map(int, [1, 2])), \\"03d\\") + str(isinstance(1, int))')"}
- log: {message: "$(eval 'os.path.basename(\\"/x/y\\") + str(pi > 3)' 'os,math')"}
""")
    plan = resolve(load(path), {}, str(path))
    assert [s.message for s in plan.steps if hasattr(s, "message")] == ["003True", "yFalse" if False else "yTrue"]
    assert plan.arguments[0].choices == ("a", "b")
    with pytest.raises(LaunchError, match="not one of its choices"):
        resolve(load(path), {"mode": "c"}, str(path))


def test_launch_ros_imports_inside_a_function_called_at_event_time(fake_run) -> None:
    run = fake_run(
        IMPORTS
        + """
def later(context):
    from launch_ros.actions import Node
    return [Node(package="robot_state_publisher", executable="robot_state_publisher", name="late_node")]

def generate_launch_description():
    return LaunchDescription([
        ExecuteProcess(cmd=["sleep", "100"], name="keepalive"),
        TimerAction(period=0.5, actions=[OpaqueFunction(function=later)]),
    ])
""",
        suffix=".launch.py",
    )
    run.advance(0.6)
    assert started(run) == ["keepalive", "late_node"]


def test_unset_launch_configuration_and_event_time_errors_fail_the_launch_as_ros(fake_run) -> None:
    run = fake_run(
        IMPORTS
        + """
def generate_launch_description():
    return LaunchDescription([
        SetLaunchConfiguration("x", "1"),
        UnsetLaunchConfiguration("x"),
        ExecuteProcess(cmd=["sleep", "100"], name="keepalive"),
        TimerAction(period=0.5, actions=[LogInfo(msg=LaunchConfiguration("x"))]),
    ])
""",
        suffix=".launch.py",
    )
    run.advance(0.6)
    run.advance(0.1)
    assert run.sup.done and run.sup.exit_code == 1
    assert any("Caught exception in launch" in m and "'x' is not set" in m for m in logs(run))


@pytest.mark.slow
def test_a_lifecycle_node_is_driven_by_change_state_events_and_its_transitions(router, launch_run) -> None:
    data = Path(__file__).parent / "data" / "lifecycle"
    run = launch_run(str(data / "managed.launch.py"), "--no-router")
    assert run.wait(30) == 0, run.text()
    text = run.text()
    order = ["configuring", "now inactive", "activating", "now active", "shutting down: managed node is active"]
    positions = [text.index(m) for m in order]
    assert positions == sorted(positions), text
    assert run.leftovers() == []


def test_the_flags_that_restore_ros2_launchs_behaviour(launch_run, tmp_path: Path) -> None:
    path = tmp_path / "flags.launch.py"
    path.write_text(
        IMPORTS
        + """
def generate_launch_description():
    return LaunchDescription([
        SetEnvironmentVariable("SET_BY_LAUNCH", "1"),
        OpaqueFunction(function=lambda context: [LogInfo(msg="os.environ " + os.environ.get("SET_BY_LAUNCH", "-"))]),
        ExecuteProcess(cmd=["sh", "-c", "echo to-stdout; echo to-stderr >&2; exit 3"], name="talker",
                       on_exit=Shutdown()),
    ])
"""
    )
    ros = ("--output-default", "log", "--exit-code", "ros", "--process-names", "ros", "--signal", "process")
    run = launch_run(str(path), "--no-router", *ros)
    assert run.wait(20) == 0, run.text()  # ros2 launch: a process's failure is not the launch's
    text = run.text()
    assert "[talker-1] to-stderr" in text and "to-stdout" not in text  # output='log': stdout to the log only
    assert "os.environ 1" in text  # the launch environment is the launcher's own, as ROS's
    run = launch_run(str(path), "--no-router")
    assert run.wait(20) == 1 and "[talker] to-stdout" in run.text()


@pytest.mark.slow
def test_python_composable_nodes_load_into_one_container_and_cpp_ones_are_one_clear_error(
    router, launch_run, tmp_path: Path
) -> None:
    data = Path(__file__).parent / "data" / "composable"
    run = launch_run(str(data / "composed.launch.py"), "--no-router")
    run.wait_for(r"Loaded node '/talker2' in container '/my_container'", timeout_s=30)
    text = run.text()
    assert "component /ns/talker1 says hello" in text and "component /talker2 says hi" in text
    assert "Loaded node '/ns/talker1' in container '/my_container'" in text
    containers = [p for p in run.leftovers() if "component-container" in " ".join(p.cmdline())]
    assert len(containers) == 1  # one process hosts both
    run.signal(signal.SIGINT)
    assert run.wait(20) == 0, run.text()
    cpp = tmp_path / "cpp.launch.py"
    cpp.write_text(
        "from launch import LaunchDescription\n"
        "from launch_ros.actions import ComposableNodeContainer\n"
        "from launch_ros.descriptions import ComposableNode\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([ComposableNodeContainer(name='c', namespace='', "
        "composable_node_descriptions=[ComposableNode(package='composition', plugin='composition::Talker')])])\n"
    )
    with pytest.raises(LaunchError, match="'composition::Talker' is not a Python component"):
        resolve(load(cpp), {}, str(cpp))


def test_a_timer_kept_on_shutdown_still_fires_and_completion_is_wanted_when_the_action_is_visited(fake_run) -> None:
    run = fake_run(
        IMPORTS
        + """
import launch.events

def generate_launch_description():
    r = ExecuteProcess(cmd=["true"], name="r")
    return LaunchDescription([
        r,  # its OnExecutionComplete comes after it: Action.visit asked before it existed, so never
        RegisterEventHandler(OnExecutionComplete(target_action=r, on_completion=[LogInfo(msg="r complete")])),
        TimerAction(period=0.2, actions=[EmitEvent(event=launch.events.Shutdown(reason="early"))]),
        TimerAction(period=0.6, actions=[LogInfo(msg="cancelled")]),
        TimerAction(period=0.4, actions=[LogInfo(msg="kept")], cancel_on_shutdown=False),
    ])
""",
        suffix=".launch.py",
    )
    run.spawner.exit("r", 0)
    run.advance(0.3)
    assert run.sup.shutting_down and not run.sup.done  # a kept timer holds the launch open
    run.advance(0.5)
    assert run.sup.done
    assert "kept" in logs(run) and "cancelled" not in logs(run) and "r complete" not in logs(run)


def test_a_nodes_command_line_is_launch_ros_s(tmp_path: Path) -> None:
    path = tmp_path / "n.launch.py"
    path.write_text(
        "from launch import LaunchDescription\nfrom launch_ros.actions import Node\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([Node(executable='sleep', name='n', namespace='ns', arguments=['5'],\n"
        "                                   ros_arguments=['--log-level', 'debug'], remappings=[('a', 'b')])])\n"
    )
    (spec,) = resolve(load(path), {}, str(path)).processes.values()
    # `<exe> <arguments> --ros-args <ros_arguments> --ros-args -r __node -r __ns … -r remaps` (node.py, Jazzy)
    assert commandline.argv(spec)[1:] == [
        "5", "--ros-args", "--log-level", "debug", "--ros-args", "-r", "__node:=n", "-r", "__ns:=/ns", "-r", "a:=b"
    ]


def test_the_launch_prefix_configuration_applies_to_processes_without_their_own(tmp_path: Path) -> None:
    path = tmp_path / "p.launch.yaml"
    path.write_text("""
launch:
- let: {name: launch-prefix, value: "nice -n 5"}
- executable: {cmd: "sleep 1", name: a}
- executable: {cmd: "sleep 2", name: b, launch_prefix: "env"}
- let: {name: launch-prefix-filter, value: "tru.*"}
- executable: {cmd: "sleep 3", name: c}
- executable: {cmd: "true", name: d}
""")
    procs = resolve(load(path), {}, str(path)).processes
    assert procs["a"].argv == ("nice", "-n", "5", "sleep", "1") and procs["b"].argv == ("env", "sleep", "2")
    assert procs["c"].argv == ("sleep", "3") and procs["d"].argv == ("nice", "-n", "5", "true")
