"""Python launch files written for ROS 2: each class community files import from launch / launch_ros.

Descriptions are resolved for real; runtime behaviour (callable handlers, EmitEvent, OnProcessIO) is driven
through the supervisor on a fake clock and fake processes, and once through a real launcher.
"""

from __future__ import annotations

import os
import re
import shutil
import signal
import textwrap
from pathlib import Path

import pytest

from diffctl.errors import LaunchError
from diffctl.launch_legacy.loader import load
from diffctl.launch_legacy.plan import LogMessage, RequestShutdown, Skipped, StartProcess, StartTimer, walk
from diffctl.launch_legacy.resolver import resolve

IMPORTS = """
import os
import signal
import sys
from launch import LaunchDescription, LaunchContext
from launch.actions import (DeclareLaunchArgument, EmitEvent, ExecuteProcess, GroupAction, IncludeLaunchDescription,
                            LogInfo, OpaqueFunction, RegisterEventHandler, SetEnvironmentVariable, TimerAction)
from launch.conditions import IfCondition, LaunchConfigurationEquals, UnlessCondition
from launch.event_handlers import OnProcessExit, OnProcessIO, OnProcessStart, OnShutdown
from launch.events import Shutdown, matches_action
from launch.events.process import ShutdownProcess, SignalProcess
from launch.launch_description_sources import AnyLaunchDescriptionSource, PythonLaunchDescriptionSource
from launch.substitutions import (AndSubstitution, Command, EnvironmentVariable, EqualsSubstitution, FindExecutable,
                                  LaunchConfiguration, NotSubstitution, OrSubstitution, PathJoinSubstitution,
                                  PythonExpression, TextSubstitution)
from launch_ros.actions import Node, PushRosNamespace, PushROSNamespace, SetParameter, SetRemap
from launch_ros.parameter_descriptions import ParameterValue, ParameterFile
from launch_ros.substitutions import FindPackageShare
from launch_xml.launch_description_sources import XMLLaunchDescriptionSource
"""


def write(tmp_path: Path, body: str, name: str = "t.launch.py") -> Path:
    path = tmp_path / name
    path.write_text(IMPORTS + "\n\n" + textwrap.dedent(body).strip() + "\n")
    return path


def plan_of(tmp_path: Path, body: str, arguments: dict[str, str] | None = None):
    path = write(tmp_path, body)
    return resolve(load(path), arguments or {}, str(path))


def messages(steps) -> list[str]:
    return [s.message for s in walk(steps) if isinstance(s, LogMessage)]


def procs(plan) -> dict:
    return {s.spec.name: s.spec for s in walk(plan.steps) if isinstance(s, StartProcess)}


def test_substitutions(tmp_path: Path, monkeypatch) -> None:
    monkeypatch.setenv("DIFFCTL_PY_T", "env-value")
    plan = plan_of(
        tmp_path,
        """
        def generate_launch_description():
            n = LaunchConfiguration("n")
            return LaunchDescription([
                DeclareLaunchArgument("n", default_value="3"),
                LogInfo(msg=Command([FindExecutable(name="echo"), " ", "-n", " ", n, "x"])),
                LogInfo(msg=PathJoinSubstitution(["/a", n, TextSubstitution(text="b")])),
                LogInfo(msg=PythonExpression([n, " * 2 + math.floor(1.5)"])),
                LogInfo(msg=PythonExpression(["os.sep + str(math.floor(2.5))"], python_modules=["os", "math"])),
                LogInfo(msg=EnvironmentVariable("DIFFCTL_PY_T")),
                LogInfo(msg=EnvironmentVariable("DIFFCTL_PY_UNSET", default_value="dflt")),
                LogInfo(msg=[AndSubstitution("true", "1"), OrSubstitution("false", "0"), NotSubstitution("false")]),
                LogInfo(msg=EqualsSubstitution(n, "3.0")),
                LogInfo(msg=FindPackageShare("ros_gz_sim")),
            ])
        """,
    )
    got = messages(plan.steps)
    assert got[:7] == ["3x", "/a/3/b", "7", os.sep + "2", "env-value", "dflt", "truefalsetrue"]
    assert got[7] == "true"  # numbers compare as numbers
    assert Path(got[8]).is_dir()
    echo = shutil.which("echo")
    assert echo is not None


def test_find_executable_prefers_this_interpreters_bin_and_fails_in_one_line(tmp_path: Path) -> None:
    import sys

    plan = plan_of(
        tmp_path,
        """
        def generate_launch_description():
            return LaunchDescription([LogInfo(msg=FindExecutable(name="xacro"))])
        """,
    )
    assert messages(plan.steps) == [str(Path(sys.executable).parent / "xacro")]
    with pytest.raises(LaunchError, match="executable 'no-such-tool-xyz' not found on the PATH"):
        plan_of(
            tmp_path,
            """
            def generate_launch_description():
                return LaunchDescription([LogInfo(msg=FindExecutable(name="no-such-tool-xyz"))])
            """,
        )


def test_parameter_value_as_str_and_parameter_file(tmp_path: Path) -> None:
    (tmp_path / "p.yaml").write_text("/**:\n  ros__parameters:\n    where: $(var place)\n")
    plan = plan_of(
        tmp_path,
        """
        def generate_launch_description():
            return LaunchDescription([
                DeclareLaunchArgument("place", default_value="home"),
                Node(package="robot_state_publisher", executable="robot_state_publisher", name="rsp", parameters=[
                    {"robot_description": ParameterValue(Command(["echo 1.0"]), value_type=str)},
                    {"typed": ParameterValue(Command(["echo 7"]))},
                    ParameterFile(os.path.join(os.path.dirname(__file__), "p.yaml"), allow_substs=True),
                ]),
            ])
        """,
    )
    spec = procs(plan)["rsp"]
    assert spec.node.params[0] == {"robot_description": "1.0\n", "typed": 7}
    assert Path(spec.node.params[1]).read_text() == "/**:\n  ros__parameters:\n    where: home\n"


def test_opaque_function_group_namespace_set_parameter_set_remap(tmp_path: Path) -> None:
    plan = plan_of(
        tmp_path,
        """
        def robots(context: LaunchContext, prefix):
            count = int(LaunchConfiguration("count").perform(context))
            assert context.launch_configurations["count"] == str(count)
            return [
                GroupAction([
                    PushRosNamespace(f"{prefix}{i}"),
                    SetParameter(name="use_sim_time", value=True),
                    SetRemap(src="cmd_vel", dst="/cmd_vel"),
                    Node(package="robot_state_publisher", executable="robot_state_publisher", name=f"rsp{i}",
                         remappings=[("odom", "/odom")]),
                ])
                for i in range(count)
            ]

        def generate_launch_description():
            return LaunchDescription([
                DeclareLaunchArgument("count", default_value="2"),
                OpaqueFunction(function=robots, args=["robot"]),
                Node(package="robot_state_publisher", executable="robot_state_publisher", name="outside"),
            ])
        """,
    )
    p = procs(plan)
    assert [p[f"rsp{i}"].node.namespace for i in range(2)] == ["/robot0", "/robot1"]
    # launch_ros passes SetParameter's as `-p name:=value`, before the node's own parameters
    assert p["rsp1"].node.global_params == (("use_sim_time", "True"),)
    assert p["rsp1"].node.remaps == (("cmd_vel", "/cmd_vel"), ("odom", "/odom"))
    assert p["outside"].node.namespace == "/" and p["outside"].node.global_params == ()
    assert p["outside"].node.remaps == ()


def test_conditions(tmp_path: Path) -> None:
    body = """
        def generate_launch_description():
            mode = LaunchConfiguration("mode")
            return LaunchDescription([
                DeclareLaunchArgument("mode", default_value="sim"),
                LogInfo(msg="is sim", condition=LaunchConfigurationEquals("mode", "sim")),
                LogInfo(msg="py", condition=IfCondition(PythonExpression(["'", mode, "' in ('sim', 'mock')"]))),
                LogInfo(msg="not real", condition=UnlessCondition(EqualsSubstitution(mode, "real"))),
            ])
    """
    assert messages(plan_of(tmp_path, body).steps) == ["is sim", "py", "not real"]
    plan = plan_of(tmp_path, body, {"mode": "real"})
    assert messages(plan.steps) == []
    assert sum(isinstance(s, Skipped) for s in plan.steps) == 3


def test_include_python_xml_and_yaml_files(tmp_path: Path) -> None:
    (tmp_path / "a.launch.xml").write_text('<launch><arg name="x"/><log message="xml $(var x)"/></launch>\n')
    (tmp_path / "b.launch.yaml").write_text("launch:\n- arg: {name: x}\n- log: {message: yaml $(var x)}\n")
    write(tmp_path, 'def generate_launch_description():\n    return LaunchDescription([LogInfo(msg="py")])', "c.py")
    plan = plan_of(
        tmp_path,
        """
        HERE = os.path.dirname(__file__)

        def generate_launch_description():
            return LaunchDescription([
                IncludeLaunchDescription(XMLLaunchDescriptionSource(os.path.join(HERE, "a.launch.xml")),
                                         launch_arguments={"x": "1"}.items()),
                IncludeLaunchDescription(AnyLaunchDescriptionSource([HERE, "/b.launch.yaml"]),
                                         launch_arguments=[("x", "2")]),
                IncludeLaunchDescription(PythonLaunchDescriptionSource(os.path.join(HERE, "c.py"))),
            ])
        """,
    )
    assert messages(plan.steps) == ["xml 1", "yaml 2", "py"]


def test_a_missing_feature_fails_in_one_line_naming_it(tmp_path: Path) -> None:
    path = tmp_path / "m.launch.py"
    path.write_text("from launch.events.process import ProcessStdin\n\ndef generate_launch_description():\n    pass\n")
    with pytest.raises(LaunchError) as info:
        load(path)
    e = info.value
    assert "launch.events.process.ProcessStdin is not supported by diffctl" in e.message
    assert e.line == 1 and "AttributeError" not in str(e)
    path.write_text("import launch_ros.actions\n\ndef generate_launch_description():\n    launch_ros.actions.Foo()\n")
    with pytest.raises(LaunchError, match=r"launch_ros\.actions\.Foo is not supported"):
        load(path)
    # Feature checks by hasattr see a missing name as absent rather than failing.
    path.write_text(
        "import launch_ros.actions\nfrom launch import LaunchDescription\n\n"
        "def generate_launch_description():\n"
        "    assert not hasattr(launch_ros.actions, 'NoSuchAction')\n"
        "    return LaunchDescription([])\n"
    )
    assert load(path).entities == []


# ---- runtime: callables, events, timers -----------------------------------------------------------------------


RUNTIME = """
def generate_launch_description():
    worker = ExecuteProcess(cmd=["sleep", "60"], name="worker")
    helper = ExecuteProcess(cmd=["sleep", "60"], name="helper")
    return LaunchDescription([
        worker,
        RegisterEventHandler(OnProcessStart(target_action=worker, on_start=lambda event, context: [
            LogInfo(msg=f"started {event.process_name} pid {event.pid}"),
            TimerAction(period=2.0, actions=[
                EmitEvent(event=SignalProcess(signal_number=signal.SIGUSR1, process_matcher=matches_action(worker))),
                helper,
            ]),
        ])),
        RegisterEventHandler(OnProcessIO(target_action=worker, on_stdout=lambda event: (
            [LogInfo(msg="saw " + event.text.decode().strip())] if event.text.startswith(b"ready") else None))),
        RegisterEventHandler(OnProcessExit(target_action=worker, on_exit=lambda event, context: [
            LogInfo(msg=f"worker returned {event.returncode}"),
            EmitEvent(event=ShutdownProcess(process_matcher=matches_action(helper))),
        ])),
        RegisterEventHandler(OnProcessExit(target_action=helper,
                                           on_exit=[EmitEvent(event=Shutdown(reason="all done"))])),
        RegisterEventHandler(OnShutdown(on_shutdown=lambda event, context: LogInfo(msg="shutdown: " + event.reason))),
    ])
"""


def test_callable_handlers_emit_events_and_start_processes_at_run_time(fake_run) -> None:
    run = fake_run(IMPORTS + RUNTIME, suffix=".launch.py", start=False)
    run.spawner.ignore["worker"] = {signal.SIGUSR1}
    run.sup.start()
    pid = run.spawner.pids["worker"]
    assert f"started worker pid {pid}" in run.text()
    run.sup.on_line("worker", "stdout", "ready to work")
    assert "saw ready to work" in run.text()
    run.advance(2.1)
    assert ("worker", "SIGUSR1") in [(n, s) for _, n, s in run.spawner.signals]
    assert run.spawner.starts("helper") == [pytest.approx(2.0, abs=0.06)]
    run.spawner.exit("worker", 3)
    assert "worker returned 3" in run.text()
    run.advance(0.1)
    assert ("helper", "SIGINT") in [(n, s) for _, n, s in run.spawner.signals]
    assert run.sup.done
    assert "shutting down: all done" in run.text() and "shutdown: all done" in run.text()


def test_print_shows_callables_without_calling_them(tmp_path: Path) -> None:
    from diffctl.launch_legacy.render import PlanView

    plan = plan_of(tmp_path, RUNTIME)
    text = "\n".join(line.plain for line in PlanView(plan).lines())
    assert "on start of worker: calls <lambda>" in text
    assert "on output (stdout) of worker: calls <lambda>" in text
    assert "on exit of executable helper" in text and "shutdown 'all done'" in text


def test_a_raising_callable_fails_the_launch_with_its_name(fake_run) -> None:
    body = """
def boom(event, context):
    raise ValueError("bad robot")

def generate_launch_description():
    p = ExecuteProcess(cmd=["true"], name="p")
    return LaunchDescription([p, RegisterEventHandler(OnProcessExit(target_action=p, on_exit=boom))])
"""
    run = fake_run(IMPORTS + body, suffix=".launch.py")
    run.spawner.exit("p", 0)
    run.advance(0.1)
    assert run.sup.done and run.sup.exit_code == 1
    assert re.search(r"OnProcessExit callable boom \(.*:\d+\) raised ValueError: bad robot", run.text())


def test_a_real_launch_of_python_callables(launch_run, tmp_path: Path) -> None:
    path = write(
        tmp_path,
        """
        def generate_launch_description():
            talker = ExecuteProcess(cmd=["sh", "-c", "echo ready; exec sleep 60"], name="talker", output="screen")
            return LaunchDescription([
                talker,
                RegisterEventHandler(OnProcessIO(target_action=talker, on_stdout=lambda e: [
                    EmitEvent(event=SignalProcess(signal_number="SIGTERM", process_matcher=matches_action(talker)))
                ] if b"ready" in e.text else None)),
                RegisterEventHandler(OnProcessExit(target_action=talker, on_exit=lambda e, c: [
                    LogInfo(msg=f"talker ended with {e.returncode}"), EmitEvent(event=Shutdown())])),
            ])
        """,
    )
    run = launch_run(str(path))
    run.wait_for(r"talker ended with -15", timeout_s=30)
    assert run.wait(30) == 0
    assert run.leftovers() == []
    assert "sending SIGTERM to [talker]" in run.text()


def test_timer_and_shutdown_in_plan(tmp_path: Path) -> None:
    plan = plan_of(
        tmp_path,
        """
        def generate_launch_description():
            return LaunchDescription([
                SetEnvironmentVariable("DIFFCTL_PY_ENV", "1"),
                TimerAction(period=LaunchConfiguration("p", default="1.5"), actions=[
                    EmitEvent(event=Shutdown(reason="timer"))]),
            ])
        """,
    )
    timer = next(s for s in plan.steps if isinstance(s, StartTimer))
    assert timer.period_s == 1.5
    assert [s.reason for s in timer.steps if isinstance(s, RequestShutdown)] == ["timer"]


def test_signal_names_are_checked(tmp_path: Path) -> None:
    with pytest.raises(LaunchError, match="'SIGFOO' is not a signal name"):
        plan_of(
            tmp_path,
            """
            def generate_launch_description():
                p = ExecuteProcess(cmd=["true"])
                return LaunchDescription([p, EmitEvent(event=SignalProcess(
                    signal_number="SIGFOO", process_matcher=matches_action(p)))])
            """,
        )
    assert signal.SIGTERM  # the module the launch files import is the standard one
