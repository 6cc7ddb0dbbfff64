"""One preloaded interpreter for all the launch tests of a `diffctl test` run, and each test's components forked
from its test, so diffctl's modules are imported once per run instead of once per process.

`diffctl test` with launch tests to run starts one fork server (supervision's zygote, the one `diffctl launch`
uses) that imports what a test and diffctl's components import (the launch's preload list plus TEST_MODULES)
and forks every launch test from it (`python -m diffctl test-child …`, re-parented to `diffctl test`, a child
subreaper, which waits and kills it as a process it started). A test so forked forks once more, first thing,
while it is still single-threaded and has no Zenoh session: that copy is its launch's fork server (handed to
the launcher spawner of its first run), and its components (`python -m diffctl …`) start with every module in
place. Each test keeps its own router and domain: a request carries the environment the launch gives it.
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

from diffctl.supervision.fork_server import ForkServer
from diffctl.supervision.zygote import PR_SET_PDEATHSIG, Preload

TEST_MODULES = (
    "pytest",
    "diffctl.testing.launch_test",
    "diffctl.testing.runner",
    "diffctl.testing.junit",
    "diffctl.testing.isolation",
    "diffctl.launch_testing.test_runner",
    "diffctl.launch_testing.loader",
    "diffctl.launch_testing.asserts",
    "diffctl.launch_testing.tools",
    "diffctl.launch_pytest.plugin",
    "diffctl.launch_pytest.tools",
    "diffctl.launch.actions.execute_process",
    "diffctl.launch.launch_service",
    "diffctl.launch_ros.actions",
    "diffctl.supervision.launcher_spawner",
    "diffctl.bus.router",
    "diffctl.client",
    "diffctl.client.node",
)


def test_preload() -> Preload:
    """The launch's preload (every component's imports and warm-ups), all of it up front, and the runner's."""
    from diffctl.cli.fork_preload import SPEC

    return Preload(modules=(*SPEC.modules, *SPEC.later, *TEST_MODULES), warm=SPEC.warm)


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

    def __init__(self) -> None:  # ForkServer's start-up (a zygote process importing the preload) is replaced
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
        self._answering()

    def for_env(self, env: Mapping[str, str]) -> InheritedForkServer:
        self._env = dict(env)
        return self


def _serve_and_become(sock: socket.socket, parent: int, start_cwd: str) -> int:
    from diffctl.supervision import zygote

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
