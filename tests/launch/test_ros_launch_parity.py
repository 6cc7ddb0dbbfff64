"""`diffctl launch` with the flags that restore ros2 launch's behaviour prints what the real Jazzy launch prints.

Each expectation below is the output of the real ros2/launch + launch_ros (jazzy, run beside diffctl on the
same file; tests cannot run it: it is not on PyPI), launcher bookkeeping lines aside (those differ by design,
README's table of differences).
"""

from __future__ import annotations

import re
from pathlib import Path

ROS_FLAGS = ("--no-router", "--output-default", "log", "--exit-code", "ros", "--signal", "process",
             "--process-names", "ros")
SHOWARGS = """#!/bin/sh
echo "argv: $*"
while [ $# -gt 0 ]; do
  if [ "$1" = "--params-file" ]; then shift; echo "params-file:"; sed 's/^/  | /' "$1"; fi
  shift
done
"""

NODES = """
import os
from launch import LaunchDescription
from launch.actions import ExecuteProcess, RegisterEventHandler, LogInfo
from launch.event_handlers import OnProcessExit
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import Parameter
EXE = os.path.join(os.path.dirname(__file__), 'showargs.sh')
def generate_launch_description():
    talker = Node(executable=EXE, name='talker', namespace='demo', arguments=['pos1'],
                  ros_arguments=['--log-level', 'debug'], output='screen',
                  parameters=[Parameter('rate', 5), {'frame': 'base'}, Parameter('label', 'abc')])
    seven = ExecuteProcess(cmd=['sh', '-c', 'exit 7'], name='seven')
    return LaunchDescription([
        RegisterEventHandler(OnProcessExit(target_action=talker, on_exit=[seven])),
        RegisterEventHandler(OnProcessExit(
            target_action=seven,
            on_exit=lambda event, context: [
                LogInfo(msg=f'{event.action.name} exited {event.returncode}'),
                Node(executable=EXE, exec_name='bare', output='screen')])),
        talker,
    ])
"""


def _screen(text: str) -> list[str]:
    """Process output and LogInfo lines, the run's log directory (the params file) as <PARAMS>."""
    lines = []
    for line in text.splitlines():
        if line.startswith("[INFO] [launch.user]") or re.match(r"\[(showargs\.sh|bare|seven)-\d\] ", line):
            lines.append(re.sub(r"--params-file \S+", "--params-file <PARAMS>", line))
    return lines


def test_nodes_labels_ros_args_parameters_and_the_final_process_name(launch_run, tmp_path: Path) -> None:
    exe = tmp_path / "showargs.sh"
    exe.write_text(SHOWARGS)
    exe.chmod(0o755)
    launch = tmp_path / "nodes.launch.py"
    launch.write_text(NODES)
    run = launch_run(*ROS_FLAGS, str(launch))
    assert run.wait(30) == 0, run.text()
    screen = _screen(run.text())
    # Node labels are the executable's name (not the node's), `-N` from one counter; Parameter objects are
    # `-p name:=<yaml.dump of the value>` (so "5\n...\n") between the dicts' files, in the order given;
    # ros_arguments are not closed by `--`; a node with nothing to pass still gets `--ros-args`;
    # event.action.name is the final name; LogInfo is logger launch.user.
    assert screen[:5] == [
        "[showargs.sh-1] argv: pos1 --ros-args --log-level debug --ros-args -r __node:=talker -r __ns:=/demo"
        " -p rate:=5",
        "[showargs.sh-1] ...",
        "[showargs.sh-1]  --params-file <PARAMS> -p label:=abc",
        "[showargs.sh-1] ...",
        "[showargs.sh-1] ",
    ]
    assert "[showargs.sh-1]   |     frame: base" in screen
    assert screen[-2:] == ["[INFO] [launch.user]: seven-2 exited 7", "[bare-3] argv: --ros-args"]



MISC = """
import launch.logging
from launch import LaunchDescription
from launch.actions import ExecuteProcess, GroupAction, LogInfo, OpaqueFunction, SetLaunchConfiguration
from launch.conditions import LaunchConfigurationEquals
from launch.substitutions import LaunchConfiguration
def report(context):
    logger = launch.logging.get_logger('my_launch')
    logger.info('mode is ' + context.perform_substitution(LaunchConfiguration('mode')))
    logger.warning('careful')
    logger.debug('not shown')
def generate_launch_description():
    return LaunchDescription([
        SetLaunchConfiguration('mode', 'fast'),
        OpaqueFunction(function=report),
        LogInfo(msg='fast mode', condition=LaunchConfigurationEquals('mode', 'fast')),
        GroupAction([
            SetLaunchConfiguration('launch-prefix', 'echo PREFIX'),
            SetLaunchConfiguration('launch-prefix-filter', 'ec.*'),
            ExecuteProcess(cmd=['echo', 'filtered in'], name='a', output='screen'),
            ExecuteProcess(cmd=['true'], name='b', output='screen'),
        ]),
        ExecuteProcess(cmd=['sh', '-c', 'sleep 0.3; echo no prefix'], name='c', output='screen'),
    ])
"""


def test_launch_prefix_get_logger_and_the_deprecation_warning(launch_run, tmp_path: Path) -> None:
    launch = tmp_path / "misc.launch.py"
    launch.write_text(MISC)
    run = launch_run(*ROS_FLAGS, str(launch))
    assert run.wait(30) == 0, run.text()
    lines = [line for line in run.text().splitlines() if not line.startswith("[INFO] [launch]")]
    # launch's UserWarning, then its loggers' screen format; `launch-prefix` (filtered by
    # `launch-prefix-filter` on the executable's name) only inside the group that set it.
    warning = lines.index(next(line for line in lines if "UserWarning: The 'LaunchConfigurationEquals'" in line))
    assert lines[warning].endswith(
        "UserWarning: The 'LaunchConfigurationEquals' and 'LaunchConfigurationNotEquals' Conditions are  deprecated."
        " Use the 'EqualsSubstitution' and 'NotEqualsSubstitution' substitutions instead! E.g.:"
    )
    assert lines[warning + 1 : warning + 4] == [
        "  IfCondition(",
        "  \tEqualsSubstitution(LaunchConfiguration('some_launch_arg'), \"some_equality_check\")",
        "  )",
    ]
    # then the source line the warning is attributed to (launch's own in ROS, the launch file's in diffctl)
    bookkeeping = re.compile(r"^\[(INFO|ERROR)\] \[(launch|[\w.]+-\d+)\]: (?!mode|careful)")
    rest = [line for line in lines[warning + 5 :] if not bookkeeping.match(line)]
    assert rest == [
        "[INFO] [my_launch]: mode is fast",
        "[WARNING] [my_launch]: careful",
        "[INFO] [launch.user]: fast mode",
        "[a-1] PREFIX echo filtered in",
        "[c-3] no prefix",
    ]


NAMESPACES = """
import os
from launch import LaunchDescription
from launch.actions import GroupAction
from launch_ros.actions import Node, PushRosNamespace
EXE = os.path.join(os.path.dirname(__file__), 'showargs.sh')
def generate_launch_description():
    def node(name, **kw):
        return Node(executable=EXE, name=name, exec_name=name, output='screen', **kw)
    return LaunchDescription([
        node('none'),
        node('empty', namespace=''),
        GroupAction([PushRosNamespace(''), node('pushed')]),
        GroupAction([PushRosNamespace('a'), PushRosNamespace('b'), node('ab', namespace='c')]),
    ])
"""


def test_a_namespace_given_or_pushed_even_empty_is_passed_as_ns_slash(launch_run, tmp_path: Path) -> None:
    exe = tmp_path / "showargs.sh"
    exe.write_text(SHOWARGS)
    exe.chmod(0o755)
    launch = tmp_path / "ns.launch.py"
    launch.write_text(NAMESPACES)
    run = launch_run(*ROS_FLAGS, str(launch))
    assert run.wait(30) == 0, run.text()
    argv = dict(re.findall(r"^\[(\w+)-\d+\] argv: (.*)$", run.text(), re.MULTILINE))
    # launch_ros (jazzy) on the same nodes: `__ns` only once a namespace is given or pushed, then `/` too
    assert argv == {
        "none": "--ros-args -r __node:=none",
        "empty": "--ros-args -r __node:=empty -r __ns:=/",
        "pushed": "--ros-args -r __node:=pushed -r __ns:=/",
        "ab": "--ros-args -r __node:=ab -r __ns:=/a/b/c",
    }
