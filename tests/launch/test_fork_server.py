"""The fork server: diffctl components forked from a pre-imported zygote behave as exec'd processes do.

Real processes throughout: a real zygote, real `python -m diffctl router` components (they run until
signalled and show their own argv by listening where it says), observed through /proc and psutil.
"""

from __future__ import annotations

import os
import signal
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import psutil
import pytest

from bench.ports import free_port, wait_port
from diffctl.cli.fork_preload import SPEC
from diffctl.launch_legacy.environment import default_child_env
from diffctl.launch_legacy.fork_server import ForkServer
from diffctl.launch_legacy.process_state import Child
from diffctl.launch_legacy.spawner import PosixSpawner


def _environ(pid: int) -> dict[str, str]:
    raw = Path(f"/proc/{pid}/environ").read_bytes()
    return dict(item.split("=", 1) for item in raw.decode(errors="replace").split("\0") if "=" in item)


def _preloaded(pid: int) -> bool:
    """A forked component maps what the zygote imported (pybullet), which `diffctl router` never imports."""
    return "pybullet" in Path(f"/proc/{pid}/maps").read_text()


class Server:
    def __init__(self, env: dict[str, str]) -> None:
        self.env = env
        self.lines: dict[int, list[object]] = {}
        self.spawner = PosixSpawner(guard=False, on_pipes=self._keep)
        self.spawner.fork_server = ForkServer(env, preexec=self.spawner.preexec, preload=SPEC)

    def _keep(self, name: str, pid: int, out: object, err: object) -> None:
        self.lines[pid] = [out, err]  # held open: a component writing to a closed pipe would die of it

    def start_router(self, port: int, cwd: str | None = None, env: dict[str, str] | None = None) -> int:
        argv = [sys.executable, "-m", "diffctl", "router", "--listen", f"tcp/127.0.0.1:{port}"]
        return self.spawner.spawn("router", argv, env or self.env, cwd, False).pid

    def wait_exit(self, pid: int, timeout_s: float = 30.0) -> int:
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            for done, code in self.spawner.reap():
                if done == pid:
                    return code
            time.sleep(0.02)
        raise AssertionError(f"pid {pid} not reaped after {timeout_s} s")


@pytest.fixture
def server() -> Iterator[Server]:
    s = Server(default_child_env(dict(os.environ, DIFFCTL_FORK_TEST="yes")))
    try:
        yield s
    finally:
        s.spawner.kill_all()
        s.spawner.close()
        for files in s.lines.values():
            for f in files:
                f.close()  # type: ignore[attr-defined]


def test_forked_components_are_separate_children_of_the_launcher_in_their_own_groups(server, tmp_path) -> None:
    ports = [free_port(), free_port()]
    pids = [server.start_router(ports[0], cwd=str(tmp_path)), server.start_router(ports[1])]
    for port in ports:
        wait_port(port, timeout_s=60)  # each listens where its own argv says
    zygote = server.spawner.fork_server.pid
    assert len(set(pids)) == 2 and zygote not in pids
    for pid, port in zip(pids, ports, strict=True):
        p = psutil.Process(pid)
        assert _preloaded(pid), "not forked from the zygote"
        assert p.ppid() == os.getpid()  # re-parented to the launcher: it waits for and reaps them
        assert os.getpgid(pid) == pid and os.getsid(pid) == pid  # own session, own group
        assert p.cmdline() == [sys.executable, "-m", "diffctl", "router", "--listen", f"tcp/127.0.0.1:{port}"]
        env = _environ(pid)
        assert env["DIFFCTL_FORK_TEST"] == "yes" and env["PYTHONUNBUFFERED"] == "1"
    assert psutil.Process(pids[0]).cwd() == str(tmp_path)
    assert psutil.Process(pids[1]).cwd() == os.getcwd()
    # Signals reach each group on its own; each is reaped here with its own status.
    server.spawner.signal_group(_child(pids[0]), signal.SIGINT)
    assert server.wait_exit(pids[0]) in (0, 130)
    assert psutil.Process(pids[1]).is_running()
    server.spawner.signal_group(_child(pids[1]), signal.SIGKILL)
    assert server.wait_exit(pids[1]) == -signal.SIGKILL


def _child(pid: int) -> Child:
    return Child(pid, pid)


def test_a_crashing_component_leaves_the_server_serving(server) -> None:
    first = server.start_router(free_port())
    os.kill(first, signal.SIGSEGV)
    assert server.wait_exit(first) == -signal.SIGSEGV
    assert psutil.Process(server.spawner.fork_server.pid).is_running()
    port = free_port()
    second = server.start_router(port)
    wait_port(port, timeout_s=60)
    assert _preloaded(second)
    server.spawner.signal_group(_child(second), signal.SIGTERM)
    assert server.wait_exit(second) in (0, -signal.SIGTERM)  # the router stops cleanly on SIGTERM once up


def test_a_component_with_an_environment_of_its_own_is_execd_and_sees_it(server) -> None:
    port = free_port()
    pid = server.start_router(port, env={**server.env, "ONLY_THIS_ONE": "1"})
    wait_port(port, timeout_s=60)
    assert _environ(pid)["ONLY_THIS_ONE"] == "1"
    assert not _preloaded(pid)
    server.spawner.signal_group(_child(pid), signal.SIGINT)
    assert server.wait_exit(pid) in (0, 130)


def test_the_launcher_forks_components_reaps_them_and_leaves_nothing(launch_run, tmp_path) -> None:
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
    pid = int(run.wait_for(r"\[zr\] started \(pid (\d+)\)", timeout_s=60).group(1))
    wait_port(port, timeout_s=60)
    assert _preloaded(pid) and psutil.Process(pid).ppid() == run.proc.pid
    # A component's exit code and its one-line error come through as from an exec'd process.
    run.wait_for(r"\[bad\] died with exit code 2", timeout_s=60)
    assert "no_such_package" in run.text()
    logs = run.log_dir.resolve()
    assert _environ(pid)["DIFFCTL_LOG_DIR"] == str(logs)  # the run's log folder, for `bag record` without -o
    run.signal(signal.SIGINT)
    assert run.wait(60) == 0, run.text()  # stopped by Ctrl-C, as with exec'd processes
    assert "[zr] stopped" in run.text()
    deadline = time.monotonic() + 10
    while run.leftovers() and time.monotonic() < deadline:
        time.sleep(0.05)
    assert [p.cmdline() for p in run.leftovers()] == []  # the zygote too
