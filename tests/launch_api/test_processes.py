"""Real child processes under ExecuteProcess: output, process groups, escalation, signals, no leftovers."""

from __future__ import annotations

import os
import select
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from diffctl.launch import LaunchDescription, LaunchService
from diffctl.launch.actions import EmitEvent, ExecuteProcess, RegisterEventHandler
from diffctl.launch.event_handlers import OnProcessIO
from diffctl.launch.events import Shutdown

# a child that starts a grandchild in its own process group, prints its pid, then waits forever
PARENT = textwrap.dedent('''
    import subprocess, sys, time
    grandchild = subprocess.Popen(['sleep', '60'])
    print('grandchild', grandchild.pid, flush=True)
    time.sleep(60)
''')

# a child that ignores SIGINT and SIGTERM: only SIGKILL ends it
STUBBORN = textwrap.dedent('''
    import signal, sys, time
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    print('ready', flush=True)
    time.sleep(60)
''')


def gone(pid: int) -> bool:
    """Ended (a zombie waiting for whoever reaps orphans counts as ended)."""
    try:
        with open(f'/proc/{pid}/stat') as f:
            return f.read().rsplit(')', 1)[1].split()[0] == 'Z'
    except FileNotFoundError:
        return True


def ends(pid: int, timeout_s: float) -> bool:
    """Whether process `pid` ends (or had ended) within `timeout_s`: its pidfd becomes readable when it exits."""
    try:
        fd = os.pidfd_open(pid)
    except ProcessLookupError:
        return True
    try:
        return bool(select.select([fd], [], [], timeout_s)[0]) or gone(pid)
    finally:
        os.close(fd)


def shutdown_when(text: str, process: ExecuteProcess, seen: list[str]) -> RegisterEventHandler:
    """Emit a Shutdown once `process` printed a line with `text` (its whole lines are collected in `seen`)."""
    partial = ['']

    def on_stdout(event):
        # chunks are as read: a line may come in pieces (an unbuffered child writes each print item alone)
        *lines, partial[0] = (partial[0] + event.text.decode()).split('\n')
        seen.extend(lines)
        if any(text in line for line in lines):
            return EmitEvent(event=Shutdown(reason='test'))
        return None

    return RegisterEventHandler(OnProcessIO(target_action=process, on_stdout=on_stdout))


def test_shutdown_signals_the_whole_group() -> None:
    seen: list[str] = []
    # the SIGINT alone must end it: no SIGTERM comes within the bound, however loaded the machine
    parent = ExecuteProcess(cmd=[sys.executable, '-c', PARENT], output='screen', sigterm_timeout='60')
    service = LaunchService(noninteractive=True)  # no terminal: launch sends the SIGINT itself
    service.include_launch_description(LaunchDescription([parent, shutdown_when('grandchild', parent, seen)]))
    assert service.run() == 0
    grandchild = int(next(line for line in seen if line.startswith('grandchild')).split()[1])
    assert parent.return_code == -signal.SIGINT
    assert ends(grandchild, 60.0), 'the SIGINT reached the process only, not its group'


def test_escalation_to_sigterm_and_sigkill_is_logged(capsys: pytest.CaptureFixture[str]) -> None:
    seen: list[str] = []
    stubborn = ExecuteProcess(cmd=[sys.executable, '-c', STUBBORN], sigterm_timeout='0.2', sigkill_timeout='0.2')
    service = LaunchService(noninteractive=True)
    service.include_launch_description(LaunchDescription([stubborn, shutdown_when('ready', stubborn, seen)]))
    assert service.run() == 0
    assert stubborn.return_code == -signal.SIGKILL
    out = capsys.readouterr().out
    name = stubborn.process_details['name']
    for step in (
        f"[INFO] [{name}]: sending signal 'SIGINT' to process[{name}]",
        f"[ERROR] [{name}]: process[{name}] failed to terminate '0.2' seconds after receiving 'SIGINT', "
        "escalating to 'SIGTERM'",
        f"[INFO] [{name}]: sending signal 'SIGTERM' to process[{name}]",
        f"[ERROR] [{name}]: process[{name}] failed to terminate '0.4' seconds after receiving 'SIGTERM', "
        "escalating to 'SIGKILL'",
        f"[INFO] [{name}]: sending signal 'SIGKILL' to process[{name}]",
    ):
        assert step in out, out


def test_output_default_and_process_label_are_options_of_the_launch_service(
    capsys: pytest.CaptureFixture[str],
) -> None:
    unsaid = ExecuteProcess(cmd=[sys.executable, '-c', 'print("hello")'], name='unsaid')
    said = ExecuteProcess(cmd=[sys.executable, '-c', 'print("hello")'], name='said', output='log')
    service = LaunchService(output_default='screen', process_label=lambda action, name: f'{name}.a')
    service.include_launch_description(LaunchDescription([unsaid, said]))
    assert service.run() == 0
    out = capsys.readouterr().out
    assert '[unsaid.a] hello' in out, out  # no output given: the service's default
    assert '[said.a]: process started' in out and '[said.a] hello' not in out, out  # 'log' given stays 'log'


LAUNCHER = textwrap.dedent('''
    import sys
    from diffctl.launch import LaunchDescription, LaunchService
    from diffctl.launch.actions import ExecuteProcess
    child = {child!r}
    service = LaunchService({options})
    service.include_launch_description(LaunchDescription(
        [ExecuteProcess(cmd=[sys.executable, '-c', child], output='screen', name='child')]))
    sys.exit(service.run())
''')

POLITE = textwrap.dedent('''
    import os, signal, sys, time
    def bye(signum, frame):
        print('got', signal.Signals(signum).name, flush=True)
        sys.exit(0)
    signal.signal(signal.SIGINT, bye)
    print('ready', os.getpid(), flush=True)
    time.sleep(60)
''')


def launcher(child: str, tmp_path: Path, options: str = '') -> tuple[subprocess.Popen, int]:
    """A script running a LaunchService with one child; returns it once the child is up, and the child's pid."""
    script = tmp_path / 'launcher.py'
    script.write_text(LAUNCHER.format(child=child, options=options))
    proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, start_new_session=True, cwd=Path(__file__).resolve().parents[2])
    for line in proc.stdout:
        if line.startswith('[child-') and 'ready' in line:
            return proc, int(line.split()[-1])
    raise AssertionError('the child never started')


@pytest.mark.parametrize(('sig', 'options', 'code', 'expect'), [
    # Ctrl-C on a terminal: the SIGINT goes on to the child's own process group, which ends politely
    (signal.SIGINT, '', 0, '[child-1] got SIGINT'),
    # SIGTERM cancels the run; the child, still alive, is ended at the end of the run
    (signal.SIGTERM, '', 1, "still running as the launch ends: sending SIGTERM"),
    # diffctl's option: SIGTERM shuts down in order, launch itself sending the child its SIGINT
    (signal.SIGTERM, 'shutdown_on_sigterm=True', 0, "[child-1] got SIGINT"),
])
def test_signals_to_the_launcher(tmp_path: Path, sig: int, options: str, code: int, expect: str) -> None:
    proc, child = launcher(POLITE, tmp_path, options)
    try:
        os.kill(proc.pid, sig)  # the launcher only, as `kill` would
        out, _ = proc.communicate(timeout=30)
        assert proc.returncode == code, out
        assert expect in out, out
        assert gone(child)
    finally:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        proc.wait()


def test_sys_exit_in_a_handler_ends_the_launch_in_order(capsys: pytest.CaptureFixture[str]) -> None:
    """sys.exit() in user code while launching: one error naming where, an orderly shutdown, rc 1."""
    from diffctl.launch.actions import OpaqueFunction
    from diffctl.launch.event_handlers import OnProcessStart

    def give_up(context) -> None:
        sys.exit(3)

    sleeper = ExecuteProcess(cmd=['sleep', '60'])
    service = LaunchService()
    service.include_launch_description(LaunchDescription([
        sleeper,
        RegisterEventHandler(OnProcessStart(target_action=sleeper, on_start=[OpaqueFunction(function=give_up)])),
    ]))
    assert service.run() == 1
    assert sleeper.return_code == -signal.SIGINT
    errors = [line for line in capsys.readouterr().out.splitlines() if line.startswith('[ERROR] [launch]')]
    assert errors == ['[ERROR] [launch]: Caught exception in launch (see debug for traceback): '
                      f'{__file__}:{give_up.__code__.co_firstlineno + 1}: SystemExit(3) raised while launching']


def test_signals_to_the_process_only_when_asked() -> None:
    """`PosixSpawner(signal_groups=False)`: ROS's behaviour, the grandchild survives the SIGINT (until the end)."""
    from diffctl.supervision import PosixSpawner

    seen: list[str] = []
    parent = ExecuteProcess(cmd=[sys.executable, '-c', PARENT])
    service = LaunchService(noninteractive=True, spawner=PosixSpawner(signal_groups=False))
    service.include_launch_description(LaunchDescription([parent, shutdown_when('grandchild', parent, seen)]))
    assert service.run() == 0
    assert parent.return_code == -signal.SIGINT
    grandchild = int(next(line for line in seen if line.startswith('grandchild')).split()[1])
    assert gone(grandchild)  # ended with the run, as a leftover of the group


def test_launch_prefix_goes_where_the_filter_matches() -> None:
    from diffctl.launch.actions import SetLaunchConfiguration

    # the prefix is `env VAR=1`: it runs what follows it, with VAR set, so the child tells whether it ran
    show = 'import os; print(os.environ.get("DIFFCTL_PREFIXED"))'
    python = ExecuteProcess(cmd=[sys.executable, '-c', show], cached_output=True)
    shell = ExecuteProcess(cmd=['sh', '-c', 'echo "$DIFFCTL_PREFIXED"'], cached_output=True)
    explicit = ExecuteProcess(cmd=['sh', '-c', 'echo "$DIFFCTL_PREFIXED"'], prefix='env DIFFCTL_PREFIXED=2',
                              cached_output=True)
    service = LaunchService()
    service.include_launch_description(LaunchDescription([
        SetLaunchConfiguration('launch-prefix', 'env DIFFCTL_PREFIXED=1'),
        SetLaunchConfiguration('launch-prefix-filter', 'pyth'),  # matched at the start of the base name
        python, shell, explicit,
    ]))
    assert service.run() == 0
    assert python.process_details['cmd'][:2] == ['env', 'DIFFCTL_PREFIXED=1']
    assert python.get_stdout().split() == ['1']
    assert python.process_details['name'].startswith('env-')  # named after the prefixed command's first word
    assert shell.process_details['cmd'][0] == 'sh' and shell.get_stdout().split() == []
    assert explicit.get_stdout().split() == ['2']  # a prefix given to the action ignores the filter


def _matcher_calls_to_start_and_stop(count: int, monkeypatch: pytest.MonkeyPatch) -> int:
    """How many times event handlers are asked about an event while `count` processes start, are stopped by
    the launch's own SIGINTs (no terminal) and exit."""
    from diffctl.launch.event_handler import BaseEventHandler
    from diffctl.launch.event_handlers import OnProcessStart

    asked = [0]
    matches = BaseEventHandler.matches

    def counted(self, event):
        asked[0] += 1
        return matches(self, event)

    monkeypatch.setattr(BaseEventHandler, 'matches', counted)
    processes = [ExecuteProcess(cmd=['sleep', '60'], name=f'p{i}', sigterm_timeout='60') for i in range(count)]
    started = []

    def on_start(event, context):
        started.append(event.pid)
        return EmitEvent(event=Shutdown(reason='all started')) if len(started) == count else None

    service = LaunchService(noninteractive=True)
    service.include_launch_description(
        LaunchDescription([RegisterEventHandler(OnProcessStart(on_start=on_start)), *processes]))
    assert service.run() == 0
    assert all(ends(pid, 10) for pid in started)
    monkeypatch.undo()
    return asked[0]


def test_starting_and_stopping_many_processes_asks_each_handler_about_its_own_process_only(
        monkeypatch: pytest.MonkeyPatch) -> None:
    # each process has handlers for its own start, output, exit and signals: were every process's handlers asked
    # about every other process's events, 4x the processes would ask ~16x as often
    few, many = (_matcher_calls_to_start_and_stop(n, monkeypatch) for n in (10, 40))
    assert many < 6 * few, (few, many)
