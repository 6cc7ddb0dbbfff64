"""The launcher with real processes: ordering, readiness, respawn, required processes, and faults.

Each launcher runs `python -m diffctl launch … --no-router`; the fixture finds every descendant by an
environment tag, so "nothing left behind" is checked against the whole system, orphans included.
"""

from __future__ import annotations

import signal
import sys
import time
from pathlib import Path

import pytest

DATA = Path(__file__).parent / "data"
PY = f"python:={sys.executable}"


def assert_nothing_left(run, within_s: float = 1.0) -> None:
    deadline = time.monotonic() + within_s
    while run.leftovers() and time.monotonic() < deadline:
        time.sleep(0.05)
    assert [p.cmdline() for p in run.leftovers()] == []


def test_start_order_follows_readiness_and_exit_handlers_and_the_launch_ends_by_itself(launch_run, tmp_path) -> None:
    record = tmp_path / "record"
    run = launch_run(str(DATA / "chain.yaml"), PY, f"record:={record}", "--no-router")
    assert run.wait(20) == 0, run.text()
    assert record.read_text().split() == ["sim", "spawn_entity", "base_spawner", "jsb_spawner", "viz"]
    text = run.text()
    # spawn_entity waited for sim's line, viz for jsb_spawner's clean exit
    assert text.index("[sim] world ready") < text.index("[spawn_entity] started")
    assert text.index("[jsb_spawner] finished cleanly") < text.index("[viz] started") < text.index("viz is up")
    assert "shutting down: all processes have exited" in text
    assert_nothing_left(run)


def test_ctrl_c_stops_every_group_escalating_for_a_stubborn_child(launch_run) -> None:
    run = launch_run(str(DATA / "supervise.yaml"), PY, "--no-router")
    run.wait_for(r"all 4 processes started")
    run.wait_for(r"\[stubborn\] ignoring SIGINT and SIGTERM")
    time.sleep(0.3)  # let talker print into its log
    run.signal(signal.SIGUSR1)
    run.wait_for(r"process +┃ pid +┃ state +┃ restarts +┃ uptime +┃ exit code")
    run.wait_for(r"│ talker +│ \d+ +│ running +│ 0 +│ \d")
    t0 = time.monotonic()
    run.signal(signal.SIGINT)
    assert run.wait(10) == 0
    took = time.monotonic() - t0
    text = run.text()
    assert "sending SIGINT to talker, stubborn, shelly, sleeper" in text
    assert "[stubborn] still running 0.3 s after SIGINT: sending SIGTERM" in text
    assert "[stubborn] still running 0.3 s after SIGTERM: sending SIGKILL" in text
    assert "[stubborn] stopped (killed by SIGKILL" in text
    assert took < 0.3 + 0.3 + 2.5, took  # generous: the machine is shared
    assert "[talker] hello" not in text  # output: log keeps stdout off the screen…
    assert (run.log_dir / "talker.log").read_text() == "hello\n"  # …and in its file
    assert "shutting down: ctrl-c (SIGINT)" in (run.log_dir / "launch.log").read_text()
    assert f"logs: {run.log_dir}" in text
    assert_nothing_left(run)


def test_sigkill_of_the_launcher_takes_every_descendant_with_it(launch_run) -> None:
    run = launch_run(str(DATA / "supervise.yaml"), PY, "--no-router")
    run.wait_for(r"all 4 processes started")
    names = {" ".join(p.cmdline()) for p in run.leftovers()}
    assert any(n == "sleep 61" for n in names), names  # the grandchild of the shell exists
    run.signal(signal.SIGKILL)
    run.wait(5)
    time.sleep(1.0)
    assert [p.cmdline() for p in run.leftovers()] == []


def test_ctrl_c_during_start_up_leaves_nothing_behind(launch_run, tmp_path) -> None:
    lines = ["launch:"]
    lines += [f"- executable: {{name: p{i}, cmd: 'sleep 60'}}" for i in range(40)]
    lines += ["- executable: {name: gated, cmd: 'sleep 60', wait_for: [{started: p39}]}"]
    lines += ["- timer: {period: 0.5, children: [{executable: {name: late, cmd: 'sleep 60'}}]}"]
    path = tmp_path / "many.yaml"
    path.write_text("\n".join(lines) + "\n")
    run = launch_run(str(path), "--no-router")
    run.wait_for(r"\[p0\] started")
    run.signal(signal.SIGINT)
    assert run.wait(10) == 0
    assert "[late] started" not in run.text()
    assert_nothing_left(run)


def test_respawn_retries_then_the_launch_reports_the_failure(launch_run, tmp_path) -> None:
    record = tmp_path / "record"
    path = tmp_path / "respawn.yaml"
    path.write_text(f"""
launch:
- executable:
    name: flaky
    cmd: "{sys.executable} {DATA / "step.py"} {record} flaky --exit 3"
    respawn: true
    respawn_delay: 0.2
    respawn_max_retries: 2
""")
    t0 = time.monotonic()
    run = launch_run(str(path), "--no-router")
    assert run.wait(15) == 1
    assert record.read_text().split() == ["flaky"] * 3
    assert time.monotonic() - t0 > 0.4  # two respawn delays
    text = run.text()
    assert "[flaky] respawning in 0.2 s (restart 2 of 2)" in text
    assert "launch failed: failed: flaky (exit code 3)" in text


def test_a_required_process_that_dies_brings_everything_down(launch_run, tmp_path) -> None:
    path = tmp_path / "required.yaml"
    path.write_text(f"""
launch:
- executable: {{name: worker, cmd: "sleep 60"}}
- executable:
    name: sim
    cmd: "{sys.executable} {DATA / "step.py"} - sim --print 'physics diverged' --sleep 0.3 --exit 4"
    on_exit: shutdown
""")
    run = launch_run(str(path), "--no-router")
    assert run.wait(10) == 1
    text = run.text()
    assert "required process 'sim' died with exit code 4 (last output: 'physics diverged')" in text
    assert "[worker] stopped (killed by SIGINT" in text
    assert_nothing_left(run)


def test_bad_input_exits_2_with_one_line_and_starts_nothing(launch_run, tmp_path) -> None:
    path = tmp_path / "bad.yaml"
    path.write_text("launch:\n- executable: {cmd: 'sleep 60', name: ok}\n- node: {pkg: rviz2, exec: rviz}\n")
    run = launch_run(str(path))
    assert run.wait(10) == 2
    lines = run.text().strip().splitlines()
    assert len(lines) == 1 and "bad.yaml:3:3: node rviz2/rviz: package 'rviz2' has no executable 'rviz'" in lines[0]
    assert not run.log_dir.exists()
    assert run.leftovers() == []


def test_yaml_and_python_forms_print_the_same_tree(tmp_path) -> None:
    import subprocess

    def printed(name: str) -> list[str]:
        done = subprocess.run(
            [sys.executable, "-m", "diffctl", "launch", str(DATA / name), "--print", "--no-color", "gui:=true"],
            capture_output=True,
            text=True,
            timeout=30,
        )
        assert done.returncode == 0, done.stderr
        return done.stdout.splitlines()[1:]  # the first line names the file

    yaml_tree = printed("tutorial.yaml")
    assert yaml_tree == printed("tutorial.launch.py")
    assert any("process rviz2" in line for line in yaml_tree)
    assert any("param robot_description = '<?xml" in line for line in yaml_tree)


@pytest.mark.slow
def test_readiness_on_a_topic_through_the_embedded_router(launch_run, tmp_path, monkeypatch) -> None:
    from tests.conftest import free_port

    monkeypatch.setenv("DIFFCTL_ROUTER", f"tcp/127.0.0.1:{free_port()}")
    path = tmp_path / "topic.yaml"
    path.write_text(f"""
launch:
- executable:
    name: waiter
    cmd: "{sys.executable} {DATA / "step.py"} - waiter --print 'topic is up' --sleep 60"
    wait_for: [{{topic: /launch_test_ready}}]
    wait_timeout: 30
- timer:
    period: 1.0
    children:
    - executable:
        name: talker
        cmd: "{sys.executable} -m diffctl topic pub /launch_test_ready std_msgs/msg/String '{{data: hi}}' --rate 5"
""")
    run = launch_run(str(path))
    run.wait_for(r"\[waiter\] topic is up", timeout_s=30)
    text = run.text()
    assert text.index("[talker] started") < text.index("[waiter] started")
    run.signal(signal.SIGTERM)  # a service manager's stop: as graceful as Ctrl-C
    assert run.wait(10) == 0
    assert "shutting down: SIGTERM received" in run.text()
    assert_nothing_left(run)


def test_show_args_prints_what_ros2_launch_show_args_prints(tmp_path) -> None:
    import subprocess

    # Expected text: `ros2 launch FILE --show-args` of the real Jazzy launch/launch_yaml on this very file.
    launch = tmp_path / "args.launch.yaml"
    launch.write_text(
        "launch:\n"
        "- arg: {name: robot, default: bot, description: robot name}\n"
        "- arg: {name: mode, default: a, choice: [{value: a}, {value: b}]}\n"
        "- arg: {name: pick, default: x, description: pick one, choice: [{value: x}, {value: y}]}\n"
        "- arg: {name: req}\n"
    )
    done = subprocess.run(
        [sys.executable, "-m", "diffctl", "launch", str(launch), "--show-args", "--no-color"],
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout == (
        "Arguments (pass arguments as '<name>:=<value>'):\n"
        "\n    'robot':\n        robot name\n        (default: 'bot')\n"
        "\n    'mode':\n        One of: ['a', 'b']\n        (default: 'a')\n"
        "\n    'pick':\n        pick one. Valid choices are: ['x', 'y']\n        (default: 'x')\n"
        "\n    'req':\n        no description given\n"
    )
    # A default made of substitutions is described as launch describes it, not evaluated (same real run).
    subs = tmp_path / "subs.launch.yaml"
    subs.write_text(
        "launch:\n- arg: {name: a, default: x}\n- arg: {name: b, default: \"pre-$(var a)\"}\n"
        "- arg: {name: c, default: \"$(env HOME)/x\"}\n"
    )
    done = subprocess.run(
        [sys.executable, "-m", "diffctl", "launch", str(subs), "--show-args"],
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert done.stdout.endswith(
        "\n    'b':\n        no description given\n        (default: 'pre-' + LaunchConfig('a'))\n"
        "\n    'c':\n        no description given\n        (default: EnvVar('HOME') + '/x')\n"
    ), done.stdout + done.stderr
    empty = tmp_path / "none.launch.yaml"
    empty.write_text("launch:\n- log: {message: x}\n")
    done = subprocess.run(
        [sys.executable, "-m", "diffctl", "launch", str(empty), "--show-args"],
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert done.stdout == "Arguments (pass arguments as '<name>:=<value>'):\n\n  No arguments.\n"


def test_a_background_job_left_by_a_finished_shell_gets_sigterm_at_once(launch_run, tmp_path) -> None:
    # A non-interactive shell's background job ignores SIGINT; with sigterm_timeout 120 a SIGINT-first stop
    # would keep it (and the launch) alive for two minutes.
    launch = tmp_path / "bg.yaml"
    launch.write_text(
        "launch:\n- executable: {cmd: \"sh -c 'sleep 300 & sleep 1; exit 0'\", name: bg, sigterm_timeout: 120}\n"
    )
    run = launch_run(str(launch), "--no-router")
    run.wait_for(r"\[bg\] exited but left processes in its group; sending them SIGTERM", timeout_s=30)
    run.wait_for(r"\[bg\] the rest of its process group is gone", timeout_s=30)
    assert run.wait(30) == 0, run.text()
    ran = float(run.wait_for(r"\[bg\] finished cleanly \(pid \d+, ran ([\d.]+) s\)").group(1))
    assert ran >= 1.0  # the shell slept a second before exiting: the figure counts from its start
    assert_nothing_left(run)


def test_children_and_command_substitutions_find_the_venvs_tools_without_activation(launch_run, tmp_path) -> None:
    bindir = str(Path(sys.executable).parent)
    launch = tmp_path / "tools.launch.xml"
    launch.write_text(
        "<launch>\n"
        "  <log message=\"command: $(command 'sh -c \\'command -v xacro\\'')\"/>\n"
        '  <executable cmd="sh -c \'command -v diffctl\'" name="child" output="screen"/>\n'
        "</launch>\n"
    )
    run = launch_run(str(launch), "--no-router", env={"PATH": "/usr/bin:/bin"})
    assert run.wait(30) == 0, run.text()
    assert f"command: {bindir}/xacro" in run.text()
    assert f"[child] {bindir}/diffctl" in run.text()


def test_ctrl_c_sends_sigterm_at_once_to_what_a_stopped_shell_left_and_counts_each_run(launch_run, tmp_path) -> None:
    # The shell and its foreground sleep go on SIGINT; its background job ignores SIGINT (as every job of a
    # non-interactive shell does) and would have outlived the default 5 s sigterm_timeout.
    launch = tmp_path / "job.yaml"
    launch.write_text(
        "launch:\n"
        "- executable: {cmd: \"sh -c 'sleep 1000 & sleep 1000'\", name: job}\n"
        "- executable: {cmd: 'sleep 1000', name: plain}\n"
    )
    run = launch_run(str(launch), "--no-router")
    run.wait_for(r"all 2 processes started", timeout_s=30)
    deadline = time.monotonic() + 10
    while sum(" ".join(p.cmdline()) == "sleep 1000" for p in run.leftovers()) < 3 and time.monotonic() < deadline:
        time.sleep(0.05)
    time.sleep(1.5)
    t0 = time.monotonic()
    run.signal(signal.SIGINT)
    assert run.wait(10) == 0, run.text()
    took = time.monotonic() - t0
    text = run.text()
    assert "[job] left processes in its group; sending them SIGTERM" in text
    assert "still running" not in text  # no timeout was waited out
    assert took < 1.0, (took, text)
    for name in ("job", "plain"):
        ran = float(run.wait_for(rf"\[{name}\] stopped \(killed by SIGINT, pid \d+, ran ([\d.]+) s\)").group(1))
        assert ran >= 1.5, text  # counted from each one's start, not from the shutdown
    assert float(run.wait_for(r"\[job\] the rest of its process group is gone, ran ([\d.]+) s").group(1)) >= 1.5
    assert_nothing_left(run)


def test_exit_code_ros_makes_an_error_in_the_launch_file_exit_1(tmp_path) -> None:
    import subprocess

    # ros2 launch (Jazzy) on this file: `Caught exception in launch (see debug for traceback): Argument "color"
    # provided value "green" is not valid. Valid options are: ['red', 'blue']`, rc 1. diffctl: exit 2 by default.
    launch = tmp_path / "choice.launch.py"
    launch.write_text(
        "from launch import LaunchDescription\n"
        "from launch.actions import DeclareLaunchArgument\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([DeclareLaunchArgument('color', default_value='red', choices=['red', 'blue'])])\n"
    )
    for flags, code in (((), 2), (("--exit-code", "ros"), 1)):
        done = subprocess.run(
            [sys.executable, "-m", "diffctl", "launch", "--no-router", *flags, str(launch), "color:=green"],
            capture_output=True,
            text=True,
            timeout=30,
        )
        assert done.returncode == code, done.stdout + done.stderr
        assert "choice.launch.py:4" in done.stderr and "'green'" in done.stderr
