"""One preloaded interpreter for all the launch tests of a `diffctl test` run, and each test's components
forked from its test, so diffctl's modules are imported once per run instead of once per process.

`diffctl test` with launch tests to run starts one fork server (diffctl/launch_legacy/zygote.py) that imports
what a launch test and diffctl's components import (the launch's own preload list plus the test runner) and
forks every launch test from it (`python -m diffctl test-child …`, re-parented to `diffctl test`, a child
subreaper, which waits and kills it as a process it started). A test so forked forks once more, first thing,
while it is still single-threaded and has no Zenoh session: that copy is its launch's fork server, and its
components (`python -m diffctl …`) start with every module in place. Each test keeps its own router and
domain: the environment of each request is the one the launch gives that process.
"""

from __future__ import annotations

import atexit
import contextlib
import ctypes
import os
import signal
import socket
import sys
import traceback
from collections.abc import Mapping

from diffctl.launch_legacy.fork_server import ForkServer, is_component
from diffctl.launch_legacy.zygote import PR_SET_PDEATHSIG, Preload

PR_SET_CHILD_SUBREAPER = 36
# Environment variables diffctl reads only when it needs them (never at import or in a warm-up), so a process
# forked from a zygote that lacks them behaves as one exec'd with them: Gazebo's resource and plugin paths.
CALL_TIME_PREFIXES = ("GZ_", "IGN_", "GAZEBO_", "SDF_PATH")
TEST_MODULES = (
    "pytest",
    "diffctl.testing.launch_test",
    "diffctl.testing.runner",
    "diffctl.testing.junit",
    "diffctl.testing.isolation",
    "diffctl.testing.service",
    "diffctl.testing.handlers",
    "diffctl.bus.router",
    "diffctl.client",
    "diffctl.client.node",
    "diffctl.launch_legacy.supervisor",
    "diffctl.launch_legacy.spawner",
)


def test_preload() -> Preload:
    """The launch's preload (every component's imports and warm-ups), all of it up front, and the runner's."""
    from diffctl.cli.fork_preload import SPEC

    return Preload(modules=(*SPEC.modules, *SPEC.later, *TEST_MODULES), warm=SPEC.warm)


def become_subreaper() -> bool:
    if not sys.platform.startswith("linux"):
        return False
    try:
        return ctypes.CDLL(None, use_errno=True).prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False


class _Forked:
    """What ForkServer keeps of its zygote's process (pid, kill, wait), for a zygote forked from here."""

    def __init__(self, pid: int) -> None:
        self.pid = pid

    def kill(self) -> None:
        with contextlib.suppress(ProcessLookupError):
            os.kill(self.pid, signal.SIGKILL)

    def wait(self, timeout: float | None = None) -> int:
        with contextlib.suppress(ChildProcessError):
            return os.waitpid(self.pid, 0)[1]
        return 0


class InheritedForkServer(ForkServer):
    """A fork server that is a fork of this process (which has the modules already): no imports of its own.

    Its components take the environment of each request; `for_env` sets the environment a launch gives, so
    only commands exec would start identically are forked (as ForkServer.accepts decides)."""

    def __init__(self) -> None:  # ForkServer's start-up is replaced, not extended
        ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        parent = os.getpid()
        start_cwd = os.getcwd()
        pid = os.fork()
        if pid == 0:  # the zygote: serve, and in a forked component, run it and never come back here
            code = 1
            try:
                ours.close()
                signal.signal(signal.SIGINT, signal.SIG_IGN)
                ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
                code = _serve_and_become(theirs, parent, start_cwd)
            finally:
                os._exit(code)
        theirs.close()
        self._env: dict[str, str] = {}
        self._sock: socket.socket | None = ours
        self.process = _Forked(pid)  # type: ignore[assignment]

    def for_env(self, env: Mapping[str, str]) -> InheritedForkServer:
        self._env = dict(env)
        return self

    def accepts(self, argv: list[str], env: Mapping[str, str], interactive: bool) -> bool:
        """As ForkServer's, but for Gazebo's search paths, which launch files set for the processes after them
        (ros_gz_sim's gz_sim.launch.py: GZ_SIM_RESOURCE_PATH) and which nothing reads before it needs them:
        the component gets them in its os.environ (not in /proc/PID/environ, which shows the zygote's)."""
        if self._sock is None or interactive or not is_component(argv):
            return False
        keys = set(env) | set(self._env)
        return all(env.get(k) == self._env.get(k) or k.startswith(CALL_TIME_PREFIXES) for k in keys)


def _serve_and_become(sock: socket.socket, parent: int, start_cwd: str) -> int:
    from diffctl.launch_legacy import zygote

    request = zygote.serve(sock, parent)
    if request is None:
        return 0
    # the component: what the interpreter does with `python -m diffctl …`, exit code and atexit included
    atexit._clear()  # the test's exit handlers are not the component's
    try:
        zygote.become(request, start_cwd)
        code = 0
    except SystemExit as e:
        if e.code is None or isinstance(e.code, int):
            code = e.code or 0
        else:
            print(e.code, file=sys.stderr)
            code = 1
    except KeyboardInterrupt:
        code = 130
    except BaseException:
        traceback.print_exc()
        code = 1
    with contextlib.suppress(Exception):
        atexit._run_exitfuncs()
    with contextlib.suppress(Exception):
        sys.stdout.flush()
        sys.stderr.flush()
    return code


_INHERITED: InheritedForkServer | None = None


def start_inherited() -> None:
    """In a launch test forked from the run's zygote, before anything else: its launch's fork server."""
    global _INHERITED
    if _INHERITED is None:
        try:
            _INHERITED = InheritedForkServer()
        except OSError:
            _INHERITED = None


def take_inherited(env: Mapping[str, str]) -> InheritedForkServer | None:
    """The fork server for the launch about to start (one launch uses it; later ones exec)."""
    global _INHERITED
    server, _INHERITED = _INHERITED, None
    return server.for_env(env) if server is not None else None
