"""diffctl's supervision behind launch's spawner interface: the fork server, the guard, the subreaper.

Real processes throughout: a real zygote, real `python -m diffctl router` components (they run until
signalled and show their own argv by listening where it says), observed through /proc and psutil.
"""

from __future__ import annotations

import asyncio
import os
import select
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import psutil
import pytest

from bench.ports import free_port, wait_port
from diffctl.cli.fork_preload import SPEC
from diffctl.supervision import SpawnRequest
from diffctl.supervision.fork_server import ForkServer
from diffctl.supervision.launcher_spawner import LauncherSpawner


def _environ(pid: int) -> dict[str, str]:
    raw = Path(f"/proc/{pid}/environ").read_bytes()
    return dict(item.split("=", 1) for item in raw.decode(errors="replace").split("\0") if "=" in item)


def _preloaded(pid: int) -> bool:
    """A forked component maps what the zygote imported (pybullet), which `diffctl router` never imports."""
    return "pybullet" in Path(f"/proc/{pid}/maps").read_text()


class Sink:
    def __init__(self) -> None:
        self.out = b""
        self.err = b""

    def on_stdout(self, data: bytes) -> None:
        self.out += data

    def on_stderr(self, data: bytes) -> None:
        self.err += data


class Launcher:
    """A LauncherSpawner with a fork server, driven on a loop of its own (as a LaunchService drives it)."""

    def __init__(self, clone: str = "1") -> None:
        self.env = dict(os.environ, DIFFCTL_FORK_TEST="yes", PYTHONUNBUFFERED="1", DIFFCTL_FORK_CLONE=clone)
        self.loop = asyncio.new_event_loop()
        self.spawner = LauncherSpawner(fork_server=ForkServer(self.env, preload=SPEC))
        self.children: list = []

    def run(self, coro, timeout_s: float = 60.0):
        return self.loop.run_until_complete(asyncio.wait_for(coro, timeout_s))

    def router(self, port: int, cwd: str | None = None, env: dict[str, str] | None = None):
        return self.routers([(port, cwd)], env)[0]

    def routers(self, where: list[tuple[int, str | None]], env: dict[str, str] | None = None) -> list:
        """Routers asked for all at once (as a launch asks for its first processes), in this order."""
        requests = [
            SpawnRequest(cmd=[sys.executable, "-m", "diffctl", "router", "--listen", f"tcp/127.0.0.1:{port}"],
                         cwd=cwd, env=env or self.env)
            for port, cwd in where
        ]

        async def spawn_all():
            return await asyncio.gather(*(self.spawner.spawn(request, Sink()) for request in requests))

        children = self.run(spawn_all())
        self.children += children
        return children

    def exit_code(self, child) -> int:
        return self.run(child.complete)

    def close(self) -> None:
        self.run(self.spawner.shutdown())
        self.spawner.close()
        self.loop.close()


@pytest.fixture
def launcher(request) -> Iterator[Launcher]:
    launcher = Launcher(getattr(request, "param", "1"))
    try:
        yield launcher
    finally:
        launcher.spawner.kill_all()
        launcher.close()


# the server makes them the launcher's children by clone(CLONE_PARENT), or (DIFFCTL_FORK_CLONE=0, or where the
# kernel or the C library do not allow it) by forking twice
@pytest.mark.parametrize("launcher", ["1", "0"], indirect=True, ids=["clone", "fork-twice"])
def test_forked_components_are_separate_children_of_the_launcher_in_their_own_groups(launcher, tmp_path) -> None:
    ports = [free_port(), free_port(), free_port()]
    # sent together: each answer is matched to its own request
    children = launcher.routers([(ports[0], str(tmp_path)), (ports[1], None), (ports[2], None)])
    for port in ports:
        wait_port(port, timeout_s=60)  # each listens where its own argv says
    zygote = launcher.spawner.fork_server.pid
    pids = [c.pid for c in children]
    assert len(set(pids)) == 3 and zygote not in pids
    for pid, port in zip(pids, ports, strict=True):
        p = psutil.Process(pid)
        assert _preloaded(pid), "not forked from the zygote"
        assert p.ppid() == os.getpid()  # re-parented to the launcher: it waits for and reaps them
        assert os.getpgid(pid) == pid and os.getsid(pid) == pid  # own session, own group
        assert p.cmdline() == [sys.executable, "-m", "diffctl", "router", "--listen", f"tcp/127.0.0.1:{port}"]
        assert _environ(pid)["DIFFCTL_FORK_TEST"] == "yes"
    assert psutil.Process(pids[0]).cwd() == str(tmp_path)
    assert psutil.Process(pids[1]).cwd() == os.getcwd()
    children[2].send_signal(signal.SIGKILL)
    assert launcher.exit_code(children[2]) == -signal.SIGKILL
    # Signals reach each group on its own; each is reaped here with its own status.
    children[0].send_signal(signal.SIGINT)
    assert launcher.exit_code(children[0]) in (0, 130)
    assert psutil.Process(pids[1]).is_running()
    children[1].send_signal(signal.SIGKILL)
    assert launcher.exit_code(children[1]) == -signal.SIGKILL


def test_a_stop_signal_sent_as_soon_as_a_component_is_forked_is_never_lost(launcher) -> None:
    # The zygote ignores SIGINT; a forked component takes its own handlers only once it runs. A Ctrl-C sent to
    # its group right after the fork (the launcher's first chance) must still stop it, every time.
    for attempt in range(20):
        child = launcher.router(free_port())
        assert child.popen is None, "exec'd, not forked from the zygote"
        child.send_signal(signal.SIGINT)  # its group exists as soon as its pid is known
        assert launcher.run(child.complete, timeout_s=60) in (0, 130), f"attempt {attempt}"
    term = launcher.router(free_port())
    assert term.popen is None
    term.send_signal(signal.SIGTERM)
    assert launcher.exit_code(term) in (0, -signal.SIGTERM)


def test_a_crashing_component_leaves_the_server_serving_and_a_different_environment_is_execd(launcher) -> None:
    first = launcher.router(free_port())
    os.kill(first.pid, signal.SIGSEGV)
    assert launcher.exit_code(first) == -signal.SIGSEGV
    assert psutil.Process(launcher.spawner.fork_server.pid).is_running()
    port = free_port()
    second = launcher.router(port)
    wait_port(port, timeout_s=60)
    assert _preloaded(second.pid)
    port = free_port()
    own = launcher.router(port, env={**launcher.env, "ONLY_THIS_ONE": "1"})
    wait_port(port, timeout_s=60)
    assert _environ(own.pid)["ONLY_THIS_ONE"] == "1" and not _preloaded(own.pid)
    for child in (second, own):
        child.send_signal(signal.SIGINT)
        assert launcher.exit_code(child) in (0, 130)


def test_gazebo_search_paths_of_its_own_still_fork_a_component_which_reads_them(launcher, tmp_path) -> None:
    # gz_sim.launch.py appends GZ_SIM_RESOURCE_PATH for the processes after it; read only when needed, it must
    # not make the rest of the launch exec'd. The world is found there (and is malformed: exit 2, named).
    (tmp_path / "only_here.sdf").write_text("<sdf version='1.9'><world")
    cmd = [sys.executable, "-m", "diffctl", "sim", "run", "-s", "only_here"]
    env = {**launcher.env, "GZ_SIM_RESOURCE_PATH": str(tmp_path)}
    server = launcher.spawner.fork_server
    assert server.accepts(cmd, env, False)
    assert not server.accepts(cmd, {**env, "PYTHONPATH": str(tmp_path)}, False)
    sink = Sink()
    child = launcher.run(launcher.spawner.spawn(SpawnRequest(cmd=cmd, env=env), sink))
    assert launcher.exit_code(child) == 2
    err = sink.err.decode()
    assert str(tmp_path / "only_here.sdf") in err and "not found" not in err, err


def test_the_supervision_modules_the_fork_server_loads_import_no_launch() -> None:
    # The zygote and the launcher's side of it are loaded before the launch core (their imports overlap it);
    # the zygote alone loads no asyncio (every component would inherit it, and none uses it).
    code = (
        "import sys, diffctl.supervision.zygote\n"
        "print('asyncio' in sys.modules)\n"
        "import diffctl.supervision.fork_server, diffctl.supervision.guard\n"
        "print(sorted(m for m in sys.modules if m.startswith(('diffctl.launch', 'diffctl.supervision'))))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    asyncio_loaded, modules = out.splitlines()
    assert asyncio_loaded == "False"
    assert eval(modules) == [
        "diffctl.supervision",
        "diffctl.supervision.exit_wait",
        "diffctl.supervision.fork_server",
        "diffctl.supervision.guard",
        "diffctl.supervision.zygote",
    ]


def test_the_launcher_forks_components_reaps_them_and_leaves_nothing(launch_run, tmp_path) -> None:
    import re
    import time

    port = free_port()
    launch = tmp_path / "forked.yaml"
    launch.write_text(
        "launch:\n"
        f"- executable: {{cmd: '{sys.executable} -m diffctl router --listen tcp/127.0.0.1:{port}', name: zr}}\n"
        f"- executable: {{cmd: '{sys.executable} -m diffctl pkg prefix no_such_package', name: bad,"
        " output: screen}\n"
        "- executable: {cmd: 'sleep 300', name: plain}\n"
    )
    run = launch_run(str(launch), "--no-router")
    pid = int(run.wait_for(r"\[zr\]: process started with pid \[(\d+)\]", timeout_s=60).group(1))
    wait_port(port, timeout_s=60)
    assert _preloaded(pid) and psutil.Process(pid).ppid() == run.proc.pid
    # A component's exit code and its one-line error come through as from an exec'd process.
    run.wait_for(r"\[bad\]: process has died \[pid \d+, exit code 2", timeout_s=60)
    assert re.search(r"\[bad\] .*no_such_package", run.text())
    assert _environ(pid)["DIFFCTL_LOG_DIR"] == str(run.log_dir.resolve())  # for `bag record` without -o
    run.signal(signal.SIGINT)
    assert run.wait(60) == 0, run.text()  # stopped by Ctrl-C, as with exec'd processes
    deadline = time.monotonic() + 10
    while run.leftovers() and time.monotonic() < deadline:
        time.sleep(0.05)
    assert [p.cmdline() for p in run.leftovers()] == []  # the zygote too


def test_execd_children_get_the_death_signal_and_none_outlives_a_launcher_already_gone(tmp_path) -> None:
    # Exec'd children run through setpriv (the death signal armed before the command is exec'd, without
    # subprocess's slow fork-and-preexec path) and a shell line that execs the command only while the launcher
    # that spawned it is still its parent. The launcher here is a process of its own, killed once it spawned.
    from diffctl.supervision.launcher_spawner import _death_signal_wrapper

    assert _death_signal_wrapper(os.getpid()), "util-linux's setpriv with --pdeathsig is missing"
    ran = tmp_path / "ran"
    code = (
        "import os, subprocess, sys\n"
        "from diffctl.supervision.launcher_spawner import _death_signal_wrapper, _while_launcher_lives\n"
        "setpriv = _death_signal_wrapper(os.getpid())\n"
        "def through(argv, env, launcher=os.getpid()):\n"
        "    return _while_launcher_lives(setpriv, launcher, argv, env)\n"
        # as if the launcher had died before the signal was armed: its pid is not the parent's
        f"print(subprocess.run(through(['touch', {str(ran)!r}], os.environ, launcher=1)).returncode)\n"
        # the command's environment is the one given, PWD included (stale, or absent)
        "for env in ({'A': '1', 'PWD': '/stale'}, {'A': '1'}):\n"
        "    shown = subprocess.run(through(['/usr/bin/env'], env), env=env, capture_output=True, text=True)\n"
        "    print(sorted(shown.stdout.split()) == sorted(f'{k}={v}' for k, v in env.items()))\n"
        "child = subprocess.Popen(through(['sleep', '60'], os.environ), start_new_session=True)\n"
        "print(child.pid, flush=True)\n"
        "sys.stdin.read()\n"  # until the test kills it
    )
    launcher = subprocess.Popen([sys.executable, "-c", code], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        assert [launcher.stdout.readline().strip() for _ in range(3)] == ["1", "True", "True"]
        assert not ran.exists()
        pid = int(launcher.stdout.readline())
        fd = os.pidfd_open(pid)
        try:
            launcher.kill()
            assert select.select([fd], [], [], 30)[0], "the child outlived its launcher"
        finally:
            os.close(fd)
    finally:
        launcher.kill()
        launcher.wait()
