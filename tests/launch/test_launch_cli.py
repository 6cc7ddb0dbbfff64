"""`diffctl launch` with real processes: ordering, stopping, respawn, required processes, the exit codes, bad input.

Each launcher runs `python -m diffctl launch … --no-router`; the fixture finds every descendant by an
environment tag, so "nothing left behind" is checked against the whole system, orphans included.
"""

from __future__ import annotations

import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

DATA = Path(__file__).parent / "data"
STEP = DATA / "step.py"
CHAIN = Path(__file__).parents[1] / "launch_extensions" / "data" / "chain.yaml"
PY = f"python:={sys.executable}"


def assert_nothing_left(run, within_s: float = 2.0) -> None:
    deadline = time.monotonic() + within_s
    while run.leftovers() and time.monotonic() < deadline:
        time.sleep(0.05)
    assert [p.cmdline() for p in run.leftovers()] == []


def write(tmp_path: Path, text: str, name: str = "t.yaml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def cli(*args: str, timeout_s: float = 60) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "diffctl", "launch", *args], capture_output=True, text=True, timeout=timeout_s
    )


def test_the_start_up_chain_runs_in_order_and_the_launch_ends_by_itself(launch_run, tmp_path) -> None:
    record = tmp_path / "record"
    run = launch_run(str(CHAIN), PY, f"step:={STEP}", f"record:={record}", "--no-router")
    assert run.wait(60) == 0, run.text()
    ran = record.read_text().split()
    assert ran[:5] == ["sim", "sim:printed", "spawn_entity", "base_spawner", "jsb_spawner"]
    assert sorted(ran[5:]) == ["viz", "viz_up"]
    assert re.search(r"all \d+ processes started in \d+ ms", run.text())
    assert_nothing_left(run)


def test_ctrl_c_stops_every_group_escalating_for_a_stubborn_child(launch_run) -> None:
    run = launch_run(str(DATA / "supervise.yaml"), PY, "--no-router")
    run.wait_for(r"all 4 processes started", timeout_s=60)
    for name, line in (("stubborn", "ignoring SIGINT and SIGTERM"), ("talker", "hello")):
        deadline = time.monotonic() + 30  # both print, into their own log files only
        log = run.log_dir / f"{name}.log"  # diffctl's labels: the name alone when it is the only one
        while not (log.is_file() and line in log.read_text()):
            assert time.monotonic() < deadline, f"{name} never printed {line!r}"
            time.sleep(0.05)
    run.signal(signal.SIGUSR1)
    run.wait_for(r"process +┃ pid +┃ state +┃ restarts +┃ uptime +┃ exit code")
    run.wait_for(r"│ talker +│ \d+ +│ running +│ 0 +│ \d")
    t0 = time.monotonic()
    run.signal(signal.SIGINT)
    assert run.wait(30) == 0, run.text()
    took = time.monotonic() - t0
    text = run.text()
    assert re.search(
        r"process\[stubborn\] failed to terminate '0.3' seconds after receiving 'SIGINT', "
        r"escalating to 'SIGTERM'",
        text,
    ), text
    assert re.search(r"escalating to 'SIGKILL'", text)
    assert re.search(r"\[stubborn\]: process has died \[pid \d+, exit code -9", text)
    assert took < 0.3 + 0.6 + 5, took  # generous: the machine is shared
    assert (run.log_dir / "talker.log").read_text() == "hello\n"  # every process has its own log file…
    assert not re.search(r"\[talker\] hello", text)  # …and `output: log` keeps stdout off the screen
    assert "user interrupted with ctrl-c (SIGINT)" in (run.log_dir / "launch.log").read_text()
    assert f"logs: {run.log_dir}" in text
    assert_nothing_left(run)


def test_sigkill_of_the_launcher_takes_every_descendant_with_it(launch_run) -> None:
    run = launch_run(str(DATA / "supervise.yaml"), PY, "--no-router")
    run.wait_for(r"\[stubborn\] ignoring SIGINT and SIGTERM", timeout_s=60)
    deadline = time.monotonic() + 10
    while not any(" ".join(p.cmdline()) == "sleep 61" for p in run.leftovers()):
        assert time.monotonic() < deadline, "the shell's grandchild never started"
        time.sleep(0.05)
    run.signal(signal.SIGKILL)
    run.wait(5)
    assert_nothing_left(run)  # the guard and the death signal, also for the shell's grandchild


def test_ctrl_c_during_start_up_leaves_nothing_behind(launch_run, tmp_path) -> None:
    lines = ["launch:"]
    lines += [f"- executable: {{name: p{i}, cmd: 'sleep 60'}}" for i in range(40)]
    lines += ["- wait_for: {started: p39, children: [{executable: {name: gated, cmd: 'sleep 60'}}]}"]
    lines += ["- timer: {period: 1.5, children: [{executable: {name: late, cmd: 'sleep 60'}}]}"]
    run = launch_run(str(write(tmp_path, "\n".join(lines) + "\n")), "--no-router")
    run.wait_for(r"\[p0\]: process started")
    run.signal(signal.SIGINT)
    assert run.wait(30) == 0, run.text()
    assert not re.search(r"\[late\]: process started", run.text())
    assert_nothing_left(run)


def test_respawn_retries_then_the_launch_reports_the_failure(launch_run, tmp_path) -> None:
    record = tmp_path / "record"
    path = write(
        tmp_path,
        f"""
launch:
- executable:
    name: flaky
    cmd: "{sys.executable} {STEP} {record} flaky --exit 3"
    respawn: "true"
    respawn_delay: 0.2
    respawn_max_retries: 2
""",
    )
    t0 = time.monotonic()
    run = launch_run(str(path), "--no-router")
    assert run.wait(30) == 1, run.text()
    assert record.read_text().split() == ["flaky"] * 3
    assert time.monotonic() - t0 > 0.4  # two respawn delays
    assert re.search(r"launch failed: failed: flaky \(exit code 3\)", run.text()), run.text()


def test_a_required_process_that_dies_brings_everything_down(launch_run, tmp_path) -> None:
    path = write(
        tmp_path,
        f"""
launch:
- executable: {{name: worker, cmd: "sleep 60"}}
- executable:
    name: sim
    cmd: "{sys.executable} {STEP} - sim --print 'physics diverged' --sleep 0.3 --exit 4"
    on_exit: shutdown
""",
    )
    run = launch_run(str(path), "--no-router")
    assert run.wait(30) == 1, run.text()
    text = run.text()
    assert re.search(r"launch failed: required process 'sim' ended with exit code 4", text), text
    assert re.search(r"\[worker\]: process has died \[pid \d+, exit code -2", text)
    assert_nothing_left(run)


@pytest.mark.parametrize(
    ("name", "text", "where", "pattern"),
    [
        ("bad.yaml", "launch:\n- executable: {cmd: 'sleep 60', name: ok}\n- nod: {pkg: a, exec: b}\n", 3, "nod"),
        ("bad.launch.xml", '<launch>\n  <log mesage="x"/>\n</launch>\n', 2, "'message'"),
        (  # diffctl's older readiness form, inside the gated action: the tag it is now is shown
            "old.yaml",
            "launch:\n- executable: {cmd: 'sleep 60', name: a}\n- executable:\n    cmd: 'sleep 60'\n"
            "    wait_for: [{started: a}]\n",
            4,
            "`- wait_for: {exited: NAME, children: [ACTIONS]}`",
        ),
        (
            "bad.launch.py",
            "from launch import LaunchDescription\n\ndef generate_launch_description():\n"
            "    return LaunchDescription([undefined_name])\n",
            4,
            "undefined_name",
        ),
        (  # a tag no frontend or extension knows: the known ones, the closest first
            "tag.launch.xml",
            '<launch>\n  <executable cmd="sleep 60" name="ok"/>\n  <nod pkg="a" exec="b"/>\n</launch>\n',
            3,
            "Unrecognized entity of the type: nod (did you mean 'node'? tags known: append_env, arg,",
        ),
        (  # a substitution no frontend or extension knows, in a tag that is fine
            "sub.launch.yaml",
            "launch:\n- executable: {cmd: 'sleep 60', name: ok}\n- log: {message: '$(nosuch x)'}\n",
            3,
            "Unknown substitution: nosuch (substitutions known: all, and, anon,",
        ),
        (  # a Python package neither diffctl nor the workspace has: what to install (README, "does not provide")
            "imports.launch.py",
            "import os\n\nfrom nav2_not_provided.launch import Helper\n",
            3,
            "No module named 'nav2_not_provided' (diffctl does not provide the Python package 'nav2_not_provided': "
            "if it is a ROS 2 package, install Nav2 (ros-jazzy-navigation2",
        ),
    ],
)
def test_a_bad_launch_file_is_one_line_naming_file_and_line_exit_2_nothing_started(
    launch_run, tmp_path, name: str, text: str, where: int, pattern: str
) -> None:
    path = write(tmp_path, text, name)
    run = launch_run(str(path))
    assert run.wait(30) == 2, run.text()
    errors = [line for line in run.text().splitlines() if line.startswith("error:")]
    assert len(errors) == 1 and f"{path}:{where}" in errors[0] and pattern in errors[0], run.text()
    assert "process started" not in run.text()
    assert run.leftovers() == []


# errors that come once the launch runs, each from a timer 0.5 s after a process started
_EARLY = "ExecuteProcess(cmd=['sleep', '60'], name='early')"
_BOOM = (
    "from launch.action import Action\n"
    "from launch.frontend import expose_action\n\n"
    "@expose_action('boom')\n"
    "class Boom(Action):\n"
    "    @classmethod\n"
    "    def parse(cls, entity, parser):\n"
    "        return cls, super().parse(entity, parser)[1]\n\n"
    "    def execute(self, context):\n"
    "        raise RuntimeError('boom')\n\n"
)


@pytest.mark.parametrize(
    ("name", "text", "pattern"),
    [
        (  # a custom action that raises
            "t.launch.py",
            "from launch import LaunchDescription\nfrom launch.action import Action\n\n"
            "class Boom(Action):\n    def execute(self, context):\n        raise RuntimeError('boom')\n\n"
            "def generate_launch_description():\n"
            "    from launch.actions import ExecuteProcess, TimerAction\n"
            f"    return LaunchDescription([{_EARLY},\n"
            "        TimerAction(period=0.5, actions=[Boom()])])\n",
            r"t\.launch\.py:6: .*boom",
        ),
        (  # a substitution of launch's that fails: the line that made the action using it
            "t.launch.py",
            "from launch import LaunchDescription\nfrom launch.actions import ExecuteProcess, LogInfo, TimerAction\n"
            "from launch.substitutions import EnvironmentVariable\n\n"
            "def generate_launch_description():\n"
            f"    return LaunchDescription([{_EARLY},\n"
            "        TimerAction(period=0.5, actions=[LogInfo(msg=EnvironmentVariable('DIFFCTL_T_NEVER_SET'))])])\n",
            r"t\.launch\.py:7: .*DIFFCTL_T_NEVER_SET",
        ),
        (
            "t.launch.xml",
            '<launch>\n  <executable cmd="sleep 60" name="early"/>\n  <timer period="0.5">\n'
            '    <log message="$(env DIFFCTL_T_NEVER_SET)"/>\n  </timer>\n</launch>\n',
            r"t\.launch\.xml:4: .*DIFFCTL_T_NEVER_SET",
        ),
        (
            "t.launch.yaml",
            "launch:\n- executable: {cmd: sleep 60, name: early}\n- timer:\n    period: 0.5\n    children:\n"
            "    - log: {message: '$(env DIFFCTL_T_NEVER_SET)'}\n",
            r"t\.launch\.yaml:6: .*DIFFCTL_T_NEVER_SET",
        ),
        (  # a custom action a launch file exposes, raising where an XML file it includes uses it
            "t.launch.py",
            "import os\nfrom launch import LaunchDescription\nfrom launch.actions import IncludeLaunchDescription\n"
            "from launch.launch_description_sources import AnyLaunchDescriptionSource\n"
            + _BOOM
            + "def generate_launch_description():\n"
            "    here = os.path.dirname(__file__)\n"
            "    return LaunchDescription([\n"
            "        IncludeLaunchDescription(AnyLaunchDescriptionSource(os.path.join(here, 'boom.launch.xml')))])\n",
            r"boom\.launch\.xml:4: .*boom",
        ),
    ],
)
def test_an_error_while_the_launch_runs_stops_everything_and_exits_2(
    launch_run, tmp_path, name: str, text: str, pattern: str
) -> None:
    write(
        tmp_path,
        '<launch>\n  <executable cmd="sleep 60" name="early"/>\n  <timer period="0.5">\n    <boom/>\n'
        "  </timer>\n</launch>\n",
        "boom.launch.xml",
    )
    run = launch_run(str(write(tmp_path, text, name)), "--no-router")
    assert run.wait(30) == 2, run.text()
    caught = [line for line in run.text().splitlines() if "Caught exception in launch" in line]
    assert len(caught) == 1 and re.search(pattern, caught[0]), run.text()
    assert "process started" in run.text()  # it came while the launch ran, and stopped what had started
    assert_nothing_left(run)


def test_arguments_are_checked_before_anything_starts(tmp_path) -> None:
    path = write(
        tmp_path,
        "launch:\n- arg: {name: color, default: red, choices: [red, blue]}\n- arg: {name: robot}\n"
        "- executable: {cmd: 'sleep 60', name: never}\n",
    )
    done = cli(str(path), "--no-router", "color:=blue")
    assert done.returncode == 2 and "missing required launch argument 'robot'" in done.stderr, done.stderr
    assert "its arguments: color, robot" in done.stderr
    done = cli(str(path), "--no-router", "robot:=r2", "color:=green", "colour:=x")
    assert done.returncode == 2 and "argument 'color' is 'green', not one of its choices" in done.stderr
    assert "argument 'colour' is not declared by t.yaml (did you mean 'color'?)" in done.stderr
    # ros2 launch (Jazzy): `Caught exception in launch … Argument "color" provided value "green" is not valid`, rc 1
    done = cli(str(path), "--no-router", "--exit-code", "ros", "robot:=r2", "color:=green")
    assert done.returncode == 1, done.stderr


def test_show_args_prints_what_ros2_launch_show_args_prints(tmp_path) -> None:
    # Expected text: `ros2 launch FILE --show-args` of the real Jazzy launch/launch_yaml on these very files.
    path = write(
        tmp_path,
        "launch:\n"
        "- arg: {name: robot, default: bot, description: robot name}\n"
        "- arg: {name: mode, default: a, choice: [{value: a}, {value: b}]}\n"
        "- arg: {name: pick, default: x, description: pick one, choice: [{value: x}, {value: y}]}\n"
        "- arg: {name: req}\n",
        "args.launch.yaml",
    )
    done = cli(str(path), "--show-args")
    assert done.returncode == 0, done.stderr
    assert done.stdout == (
        "Arguments (pass arguments as '<name>:=<value>'):\n"
        "\n    'robot':\n        robot name\n        (default: 'bot')\n"
        "\n    'mode':\n        One of: ['a', 'b']\n        (default: 'a')\n"
        "\n    'pick':\n        pick one. Valid choices are: ['x', 'y']\n        (default: 'x')\n"
        "\n    'req':\n        no description given\n"
    )
    subs = write(
        tmp_path,
        'launch:\n- arg: {name: a, default: x}\n- arg: {name: b, default: "pre-$(var a)"}\n'
        '- arg: {name: c, default: "$(env HOME)/x"}\n',
        "subs.launch.yaml",
    )
    assert cli(str(subs), "--show-args").stdout.endswith(
        "\n    'b':\n        no description given\n        (default: 'pre-' + LaunchConfig('a'))\n"
        "\n    'c':\n        no description given\n        (default: EnvVar('HOME') + '/x')\n"
    )
    empty = write(tmp_path, "launch:\n- log: {message: x}\n", "none.launch.yaml")
    assert (
        cli(str(empty), "--show-args").stdout == "Arguments (pass arguments as '<name>:=<value>'):\n\n  No arguments.\n"
    )


def test_print_describes_the_entities_and_runs_no_user_code(tmp_path) -> None:
    marker = tmp_path / "ran"
    path = write(
        tmp_path,
        "from launch import LaunchDescription\nfrom launch.actions import ExecuteProcess, OpaqueFunction\n"
        "from diffctl.launch_extensions import WaitFor\n\n"
        "def touch(context):\n"
        f"    open({str(marker)!r}, 'w').close()\n\n"
        "def generate_launch_description():\n"
        "    sim = ExecuteProcess(cmd=['sleep', '1'], name='sim')\n"
        "    return LaunchDescription([sim, OpaqueFunction(function=touch),\n"
        "        WaitFor([WaitFor.exited(sim)], actions=[ExecuteProcess(cmd=['true'], name='after')])])\n",
        "p.launch.py",
    )
    done = cli(str(path), "--print")
    assert done.returncode == 0, done.stderr
    assert not marker.exists()  # ros2 launch --print calls no OpaqueFunction; nor does diffctl
    assert "ExecuteProcess(cmd=['sleep', '1']" in done.stdout and "WaitFor(exited sim)" in done.stdout
    # objects are shown as Python shows them, under the module names the user imported (ros2 launch --print's)
    assert re.match(r"<launch\.launch_description\.LaunchDescription object at 0x[0-9a-f]+>\n", done.stdout)
    assert re.search(r"Action\('<launch\.actions\.opaque_function\.OpaqueFunction object at 0x", done.stdout)
    assert "diffctl.launch" not in done.stdout, done.stdout


TLS_LAUNCH = """
import asyncio, sys
from launch import LaunchDescription
from launch.actions import ExecuteProcess, OpaqueCoroutine, OpaqueFunction, RegisterEventHandler
from launch.event_handlers import OnProcessStart

def loaded(context):
    # what the launcher has imported once its processes run: none of these, for a launch of plain processes
    heavy = ('_ssl', 'rich', 'lxml.etree')
    print('loaded:', [name for name in heavy if name in sys.modules], flush=True)

async def tls_round_trip(context, cert, key):
    import ssl  # the launch file's own import: the whole module, and asyncio's TLS with it

    server_side = ssl.create_default_context(ssl.Purpose.CLIENT_AUTH)
    server_side.load_cert_chain(cert, key)

    async def echo(reader, writer):
        writer.write(await reader.readline())
        await writer.drain()
        writer.close()

    server = await asyncio.start_server(echo, '127.0.0.1', 0, ssl=server_side)
    port = server.sockets[0].getsockname()[1]
    client_side = ssl.create_default_context(cafile=cert)
    reader, writer = await asyncio.open_connection('127.0.0.1', port, ssl=client_side, server_hostname='localhost')
    writer.write(b'over tls\\n')
    print('echoed:', (await reader.readline()).decode().strip(), flush=True)
    writer.close()
    server.close()

def generate_launch_description():
    child = ExecuteProcess(cmd=['true'], name='child')
    return LaunchDescription([child, RegisterEventHandler(OnProcessStart(target_action=child, on_start=[
        OpaqueFunction(function=loaded),
        OpaqueCoroutine(coroutine=tls_round_trip, args=[CERT, KEY])]))])
"""


def test_the_launcher_loads_tls_only_for_a_launch_file_that_uses_it(launch_run, tmp_path) -> None:
    # asyncio imports ssl (OpenSSL: over a MB of the launcher's memory), the status table rich, a workspace's
    # package.xml lxml: the launcher defers all three to their first use, which a launch file may make itself
    cert, key = tmp_path / "cert.pem", tmp_path / "key.pem"
    subprocess.run(
        ["openssl", "req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes",
         "-keyout", str(key), "-out", str(cert), "-days", "1", "-subj", "/CN=localhost"],
        check=True, capture_output=True, timeout=60,
    )
    text = TLS_LAUNCH.replace("CERT, KEY", f"{str(cert)!r}, {str(key)!r}")
    run = launch_run(str(write(tmp_path, text, "tls.launch.py")), "--no-router")
    assert run.wait(60) == 0, run.text()
    assert "loaded: []" in run.text()
    assert "echoed: over tls" in run.text()
    assert_nothing_left(run)


def test_a_background_job_left_by_a_finished_shell_gets_sigterm_at_once(launch_run, tmp_path) -> None:
    # A non-interactive shell's background job ignores SIGINT; waiting out a timeout for it would only delay
    # the inevitable.
    path = write(tmp_path, "launch:\n- executable: {cmd: \"sh -c 'sleep 300 & sleep 1; exit 0'\", name: bg}\n")
    run = launch_run(str(path), "--no-router")
    run.wait_for(r"\[bg\] exited but left processes in its group; sending them SIGTERM", timeout_s=30)
    run.wait_for(r"\[bg\] the rest of its process group is gone", timeout_s=30)
    assert run.wait(30) == 0, run.text()
    assert_nothing_left(run)


def test_children_and_command_substitutions_find_the_venvs_tools_and_jazzys_environment(launch_run, tmp_path) -> None:
    bindir = str(Path(sys.executable).parent)
    path = write(
        tmp_path,
        "<launch>\n"
        "  <log message=\"command: $(command 'sh -c \\'command -v xacro\\'') distro: $(env ROS_DISTRO)\"/>\n"
        "  <executable cmd=\"sh -c 'command -v diffctl; echo $ROS_DISTRO $ROS_VERSION $ROS_PYTHON_VERSION'\""
        ' name="child" output="screen"/>\n'
        "</launch>\n",
        "tools.launch.xml",
    )
    run = launch_run(str(path), "--no-router", env={"PATH": "/usr/bin:/bin", "ROS_DISTRO": ""})
    assert run.wait(30) == 0, run.text()
    text = run.text()
    assert f"command: {bindir}/xacro\n distro: " in text or f"command: {bindir}/xacro" in text
    assert re.search(rf"\[child\] {re.escape(bindir)}/diffctl", text)
    assert re.search(r"\[child\] +2 3", text), text  # ROS_DISTRO given (empty) stays; the rest as Jazzy


def test_the_flags_that_restore_ros2_launchs_behaviour(launch_run, tmp_path) -> None:
    path = write(
        tmp_path,
        "launch:\n"
        "- executable: {cmd: \"sh -c 'echo to-stdout; echo to-stderr >&2; sleep 60'\", name: talk}\n"
        "- executable: {cmd: \"sh -c 'sleep 0.5; exit 3'\", name: fails}\n"
        "- executable: {cmd: \"sh -c 'echo second; sleep 60'\", name: talk, output: log}\n",
    )
    ours = launch_run(str(path), "--no-router")
    ros = launch_run(
        str(path), "--no-router", "--output-default", "log", "--exit-code", "ros", "--process-names", "ros"
    )
    for run, number in ((ours, ""), (ros, r"-\d+")):
        run.wait_for(rf"\[fails{number}\]: process has died", timeout_s=30)
        run.wait_for(rf"\[talk{number}\] to-stderr")
        run.signal(signal.SIGINT)
    assert ours.wait(30) == 0 and ros.wait(30) == 0  # a failure before Ctrl-C does not fail the launch
    assert "[talk] to-stdout" in ours.text()
    assert "[talk-2]: process started" in ours.text()  # diffctl's labels: a second of a name is name-2…
    assert "[talk-2] second" not in ours.text()  # …and an `output: log` it was given keeps its stdout off the screen
    assert not re.search(r"\[talk-\d+\] to-stdout", ros.text())  # ros2 launch's: stdout to launch.log only
    assert "to-stdout" in (ros.log_dir / "launch.log").read_text()


@pytest.mark.slow
def test_readiness_on_a_topic_through_the_embedded_router_and_sigterm(launch_run, tmp_path, monkeypatch) -> None:
    from tests.conftest import free_port

    monkeypatch.setenv("DIFFCTL_ROUTER", f"tcp/127.0.0.1:{free_port()}")
    path = write(
        tmp_path,
        f"""
launch:
- wait_for:
    topic: /launch_test_ready
    timeout: 60
    children:
    - executable:
        name: waiter
        cmd: "{sys.executable} {STEP} - waiter --print 'topic is up' --sleep 60"
        output: screen
- timer:
    period: 1.0
    children:
    - executable:
        name: talker
        cmd: "{sys.executable} -m diffctl topic pub /launch_test_ready std_msgs/msg/String '{{data: hi}}' --rate 5"
""",
    )
    run = launch_run(str(path))
    run.wait_for(r"\[waiter\] topic is up", timeout_s=60)
    text = run.text()
    assert re.search(r"\[talker\]: process started", text).start() < text.index("[waiter")  # type: ignore[union-attr]
    run.signal(signal.SIGTERM)  # a service manager's stop: every process ends, and that is no failure
    assert run.wait(30) == 0, run.text()
    assert "sending signal 'SIGINT' to process[waiter]" in run.text()  # an orderly shutdown, as Ctrl-C
    assert_nothing_left(run)
