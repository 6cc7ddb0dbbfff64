"""The supervisor's decisions on a fake clock and fake processes: escalation, respawn, required, readiness."""

from __future__ import annotations

import signal

import pytest

STUBBORN = """
launch:
- executable: {cmd: "sleep 100", name: a}
- executable: {cmd: "sleep 100", name: b, sigterm_timeout: 2, sigkill_timeout: 3}
"""


def test_shutdown_signals_in_reverse_start_order_and_escalates_on_each_timeout(fake_run) -> None:
    run = fake_run(STUBBORN)
    run.spawner.ignore["b"] = {signal.SIGINT, signal.SIGTERM}
    assert [n for _, n, _ in run.spawner.spawned] == ["a", "b"]
    run.sup.on_signal(signal.SIGINT)
    run.advance(0.01)
    assert run.spawner.signals[:2] == [(0.0, "b", "SIGINT"), (0.0, "a", "SIGINT")]
    run.advance(1.9)
    assert [s for s in run.spawner.signals if s[1] == "b"] == [(0.0, "b", "SIGINT")]
    run.advance(0.2)
    assert [s[1:] for s in run.spawner.signals][-1] == ("b", "SIGTERM")
    assert run.spawner.signals[-1][0] == pytest.approx(2.0, abs=0.06)
    assert not run.sup.done
    run.advance(3.0)
    assert [s[1:] for s in run.spawner.signals][-1] == ("b", "SIGKILL")
    assert run.spawner.signals[-1][0] == pytest.approx(5.0, abs=0.06)
    assert run.sup.done and run.sup.exit_code == 0
    text = run.text()
    assert "sending SIGINT to b, a" in text
    assert "[b] still running 2 s after SIGINT: sending SIGTERM" in text
    assert "[b] still running 3 s after SIGTERM: sending SIGKILL" in text


def test_second_interrupt_kills_at_once(fake_run) -> None:
    run = fake_run(STUBBORN)
    run.spawner.ignore["a"] = run.spawner.ignore["b"] = {signal.SIGINT, signal.SIGTERM}
    run.sup.on_signal(signal.SIGINT)
    run.advance(0.5)
    run.sup.on_signal(signal.SIGINT)
    run.advance(0.01)
    assert sorted(s[1:] for s in run.spawner.signals if s[2] == "SIGKILL") == [("a", "SIGKILL"), ("b", "SIGKILL")]
    assert run.sup.done and run.sup.exit_code == 0


def test_respawn_waits_its_delay_and_stops_at_the_retry_limit(fake_run) -> None:
    run = fake_run("""
launch:
- executable: {cmd: "false", name: flaky, respawn: true, respawn_delay: 1.5, respawn_max_retries: 2}
""")
    for _ in range(3):
        run.spawner.exit("flaky", 3)
        run.advance(1.6)
    assert run.spawner.starts("flaky") == pytest.approx([0.0, 1.5, 3.1], abs=0.06)
    assert run.sup.done and run.sup.exit_code == 1
    assert "respawning in 1.5 s (restart 2 of 2)" in run.text()
    assert "launch failed: failed: flaky (exit code 3)" in run.text()


def test_a_required_process_that_dies_takes_everything_down_and_says_why(fake_run) -> None:
    run = fake_run("""
launch:
- executable: {cmd: "sleep 100", name: worker}
- executable: {cmd: "sleep 100", name: sim, on_exit: shutdown}
""")
    run.sup.on_line("sim", "stderr", "segmentation fault in physics step")
    run.spawner.exit("sim", 139)
    run.advance(0.1)
    assert run.spawner.signals == [(0.0, "worker", "SIGINT")]
    assert run.sup.done and run.sup.exit_code == 1
    assert (
        "required process 'sim' died with exit code 139 (last output: 'segmentation fault in physics step')"
        in run.text()
    )


def test_exit_handlers_chain_and_filter_on_exit_code(fake_run) -> None:
    run = fake_run("""
launch:
- executable: {cmd: "true", name: spawner_a}
- on_exit: {target: spawner_a, exit_code: 0, do: [{executable: {cmd: "true", name: on_success}}]}
- on_exit: {target: spawner_a, exit_code: 1, do: [{executable: {cmd: "true", name: on_failure}}]}
- on_start: {target: on_success, do: [{executable: {cmd: "true", name: after_start}}]}
""")
    assert [n for _, n, _ in run.spawner.spawned] == ["spawner_a"]
    run.spawner.exit("spawner_a", 0)
    assert [n for _, n, _ in run.spawner.spawned] == ["spawner_a", "on_success", "after_start"]
    run.spawner.exit("on_success", 0)
    run.spawner.exit("after_start", 0)
    assert run.sup.done and run.sup.exit_code == 0  # nothing left to do: the launch ends by itself


def test_readiness_gates_open_on_exit_and_log_line_and_a_timeout_fails_the_launch(fake_run) -> None:
    run = fake_run("""
launch:
- executable: {cmd: "sleep 1", name: sim}
- executable: {cmd: "true", name: spawn_entity, wait_for: [{log: {process: sim, regex: "world loaded"}}]}
- executable: {cmd: "sleep 100", name: spawner, wait_for: [{exited: spawn_entity}]}
- executable: {cmd: "sleep 100", name: late, wait_for: [{started: never}], wait_timeout: 4}
- timer: {period: 60, children: [{executable: {cmd: "true", name: never}}]}
""")
    assert [n for _, n, _ in run.spawner.spawned] == ["sim"]
    run.sup.on_line("sim", "stdout", "loading world")
    run.advance(0.5)
    assert [n for _, n, _ in run.spawner.spawned] == ["sim"]
    run.sup.on_line("sim", "stdout", "[INFO] world loaded in 0.4 s")
    assert [n for _, n, _ in run.spawner.spawned] == ["sim", "spawn_entity"]
    run.spawner.exit("spawn_entity", 0)
    assert [n for _, n, _ in run.spawner.spawned] == ["sim", "spawn_entity", "spawner"]
    run.advance(4.0)
    assert run.sup.shutting_down
    run.advance(0.1)
    assert run.sup.done and run.sup.exit_code == 1
    assert "late: still waiting for never started after 4 s" in run.text()
    assert "never" not in [n for _, n, _ in run.spawner.spawned]


def test_a_dependency_that_fails_fails_its_dependents_at_once(fake_run) -> None:
    run = fake_run("""
launch:
- executable: {cmd: "true", name: spawn_entity}
- executable: {cmd: "sleep 100", name: spawner, wait_for: {exited: spawn_entity}}
""")
    run.spawner.exit("spawn_entity", 2)
    run.advance(0.1)
    assert run.sup.done and run.sup.exit_code == 1
    assert "spawner: cannot wait for spawn_entity exited with code 0: spawn_entity exit code 2" in run.text()


def test_a_process_that_cannot_start_counts_as_exit_127(fake_run) -> None:
    run = fake_run(
        """
launch:
- executable: {cmd: "sleep 100", name: keeper}
- executable: {cmd: "true", name: gone, on_exit: shutdown}
""",
        start=False,
    )
    run.spawner.cannot_start.add("gone")
    run.sup.start()
    run.advance(0.1)
    assert run.sup.done and run.sup.exit_code == 1
    assert "[gone] could not start: No such file or directory" in run.text()
    assert "required process 'gone' died with exit code 127" in run.text()


def test_parameters_become_a_params_file_and_ros_args(fake_run, tmp_path) -> None:
    run = fake_run("""
launch:
- node:
    pkg: robot_state_publisher
    exec: robot_state_publisher
    name: rsp
    namespace: robot1
    param: [{name: use_sim_time, value: true}, {name: robot_description, value: "<sdf version='1.9'/>"}]
    remap: [{from: joint_states, to: /js}]
""")
    ((_, _, argv),) = run.spawner.spawned
    tail = argv[argv.index("--ros-args") :]
    assert tail[:5] == ["--ros-args", "-r", "__node:=rsp", "-r", "__ns:=/robot1"]
    assert tail[-2:] == ["-r", "joint_states:=/js"]
    params_file = tail[tail.index("--params-file") + 1]
    from diffctl.ros_args import load_params_file

    assert load_params_file(params_file, "rsp") == {"use_sim_time": True, "robot_description": "<sdf version='1.9'/>"}


def test_the_live_line_names_what_is_awaited_and_clears_once_all_are_up(fake_run) -> None:
    import io

    from diffctl.launch_legacy.output import Output

    run = fake_run(
        """
launch:
- executable: {cmd: "true", name: spawn_entity}
- executable: {cmd: "sleep 100", name: spawner, wait_for: [{exited: spawn_entity}]}
- on_exit: {target: spawner, do: [{executable: {cmd: "sleep 100", name: viz}}]}
""",
        start=False,
    )
    screen = io.StringIO()
    run.sup.output = Output(stream=screen, live=True, no_color=True)
    run.sup.start()
    assert "up: spawn_entity │ waiting: spawner (spawn_entity exited with code 0)" in screen.getvalue()
    run.spawner.exit("spawn_entity", 0)
    assert "waiting: viz (on exit of spawner)" in screen.getvalue().rsplit("\r\x1b[2K", 1)[-1]
    run.spawner.exit("spawner", 0)
    tail = screen.getvalue().rsplit("\r\x1b[2K", 1)[-1]
    assert "waiting" not in tail and "all 3 processes started in 0 ms" in tail
    run.sup.show_status()
    table = screen.getvalue().rsplit("all 3 processes started", 1)[-1]
    for header in ("process", "pid", "state", "restarts", "uptime", "exit code"):
        assert header in table
    assert "viz" in table and "running" in table and "spawn_entity" in table and "exited" in table


def test_python_descriptions_emit_shutdown_run_timers_and_on_shutdown_handlers(fake_run) -> None:
    run = fake_run(
        """
from diffctl.launch_legacy import (EmitEvent, ExecuteProcess, GroupAction, IfCondition, LaunchConfiguration,
    LaunchDescription, LogInfo, OnShutdown, RegisterEventHandler, TimerAction, UnlessCondition)
from diffctl.launch_legacy import events

def generate_launch_description():
    return LaunchDescription([
        ExecuteProcess(cmd=["sleep", "100"], name="worker"),
        GroupAction([ExecuteProcess(cmd=["sleep", "100"], name="viz")],
                    condition=UnlessCondition(LaunchConfiguration("headless", default="true"))),
        RegisterEventHandler(OnShutdown(on_shutdown=[LogInfo(msg="saving the map")])),
        TimerAction(period=2.0, actions=[EmitEvent(event=events.Shutdown(reason="demo over"))]),
    ])
""",
        suffix=".launch.py",
    )
    assert [n for _, n, _ in run.spawner.spawned] == ["worker"]
    run.advance(1.9)
    assert not run.sup.shutting_down
    run.advance(0.2)
    run.advance(0.1)
    assert run.sup.done and run.sup.exit_code == 0
    text = run.text()
    assert text.index("shutting down: demo over") < text.index("saving the map") < text.index("[worker] stopped")


def test_the_tutorials_gz_sim_include_starts_the_simulator_and_not_the_gui_client(tmp_path) -> None:
    from diffctl.launch_legacy.loader import load
    from diffctl.launch_legacy.resolver import resolve

    path = tmp_path / "tutorial_include.launch.py"
    path.write_text("""
import os
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource

def generate_launch_description():
    gazebo_launch_file = os.path.join(get_package_share_directory("ros_gz_sim"), "launch", "gz_sim.launch.py")
    world_file = os.path.join(get_package_share_directory("diffctl_demo"), "worlds", "empty.world")
    return LaunchDescription([
        IncludeLaunchDescription(PythonLaunchDescriptionSource(gazebo_launch_file),
            launch_arguments={"gz_args": [" -r -s -v4 ", world_file], "on_exit_shutdown": "true"}.items()),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(os.path.join(gazebo_launch_file)),
            launch_arguments={"gz_args": "-g -v4 "}.items()),
    ])
""")
    plan = resolve(load(path), {}, str(path))
    (sim,) = plan.processes.values()
    assert sim.argv[-5:] == ("run", "-r", "-s", "-v4", sim.argv[-1]) and sim.argv[-1].endswith("worlds/empty.world")
    assert sim.required
