"""The spawner of `diffctl launch`: the POSIX spawner, plus what makes sure nothing outlives the launcher.

- every exec'd child arms PR_SET_PDEATHSIG=SIGKILL (it dies with the launcher, even a SIGKILLed one);
- the launcher is a child subreaper (PR_SET_CHILD_SUBREAPER): orphaned grandchildren are re-parented to it
  and reaped here, not left to init;
- the guard process (guard.py) SIGKILLs every group still known if the launcher dies, which catches the
  grandchildren a death signal does not reach (a `shell: true` process's own children);
- a child that exits leaving members of its group behind (a shell's background job, which ignores SIGINT)
  has them sent SIGTERM at once, and SIGKILL if they outlast `linger_kill_s`, each step logged;
- diffctl's own components (`<python> -m diffctl …`) are forked from the fork server (fork_server.py) when
  one is given: the same session, death signal, pipes, argv and environment, without the imports.

`signal_scope='process'` signals the process alone instead of its group (ros2 launch's behaviour); groups
are still reaped at the end.
"""

from __future__ import annotations

import asyncio
import contextlib
import ctypes
import errno
import glob
import logging
import os
import shutil
import signal
import subprocess
import sys
import time
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from diffctl.supervision.exit_wait import wait_exited
from diffctl.supervision.fork_server import ForkServer
from diffctl.supervision.spawner import (
    OutputSink,
    PosixSpawner,
    SpawnRequest,
    _Child,
    _close,
    _group_alive,
)

PR_SET_PDEATHSIG = 1
PR_SET_CHILD_SUBREAPER = 36
LINGER_POLL_S = 0.05
ORPHAN_LOOK_S = 0.05
GUARD_FORGET_S = 1.0  # how long the guard may go on knowing a group that is gone


def _prctl() -> Any:
    if not sys.platform.startswith("linux"):
        return None
    try:
        return ctypes.CDLL(None, use_errno=True).prctl
    except (OSError, AttributeError):
        return None


class LauncherSpawner(PosixSpawner):
    def __init__(
        self,
        *,
        fork_server: ForkServer | None = None,
        guard: bool = True,
        signal_scope: str = "group",
        linger_kill_s: float = 5.0,
        term_timeout_s: float = 2.0,
        logger: logging.Logger | None = None,
    ) -> None:
        super().__init__(term_timeout_s=term_timeout_s, logger=logger)
        if signal_scope not in ("group", "process"):
            raise ValueError(f"signal_scope {signal_scope!r}: 'group' or 'process'")
        self.fork_server = fork_server
        self.signal_scope = signal_scope
        self.linger_kill_s = linger_kill_s
        self._prctl = _prctl()
        self._launcher = os.getpid()
        self._guard_enabled = guard
        self._guard: subprocess.Popen[bytes] | None = None
        self._guard_lines: list[str] = []  # told, not yet written
        self._guard_write_soon = False
        self._guard_write_later: asyncio.TimerHandle | None = None
        self._groups: set[int] = set()
        self._direct: set[int] = set()
        self._sigchld_loop: asyncio.AbstractEventLoop | None = None
        self._previous_sigchld: Any = None
        self._orphans_looked_for = True  # no look at the orphans is pending
        self._fork_lock: asyncio.Lock | None = None
        self._lingering: dict[int, str] = {}  # pgid → name: groups whose leader exited, sent SIGTERM
        if self._prctl is not None:
            self._prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0)
        self.preexec_fn = self._preexec if self._prctl is not None else None
        self._wrapper: list[str] | None = None  # found at the first exec (see _exec_argv)

    # ---- starting ----------------------------------------------------------------------------------------------

    def _preexec(self) -> None:
        # In the child between fork and exec: the death signal, and the race with a launcher already gone.
        self._prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
        if os.getppid() != self._launcher:
            os._exit(1)

    def _how_to_exec(self, argv: list[str], request: SpawnRequest) -> tuple[list[str], Any]:
        """`argv` run through util-linux's setpriv, which arms the death signal, and a shell line that execs it
        if the launcher is still its parent (it may have died before the signal was armed).

        A preexec_fn does the same in Python, but makes subprocess fork the whole launcher, run Python code in
        the copy (faulting its pages in one by one) and wait for that before it execs: 15-25 ms a process on a
        loaded machine, where vfork, which subprocess uses without a preexec_fn, takes 4-6. Without setpriv
        (or one too old for --pdeathsig) the preexec_fn stays."""
        if self._prctl is None:
            return argv, self.preexec_fn
        if self._wrapper is None:
            self._wrapper = _death_signal_wrapper(self._launcher)
        if not self._wrapper:
            return argv, self.preexec_fn
        if not request.shell:
            _check_executable(argv[0], request)  # the errors exec gives, raised here as Popen raises them
        env = request.env if request.env is not None else os.environ
        return _while_launcher_lives(self._wrapper, self._launcher, argv, env), None

    async def spawn(self, request: SpawnRequest, sink: OutputSink) -> _Child:
        self._watch_orphans()
        child = None
        if self.fork_server is not None and not request.shell and not request.emulate_tty:
            child = await self._fork(request, sink)
        if child is None:
            child = await super().spawn(request, sink)
        child.on_leader_exit = self._leader_exited
        self._direct.add(child.pid)
        self._groups.add(child.pgid)
        self._tell_guard(f"+{child.pgid}")
        return child

    async def _fork(self, request: SpawnRequest, sink: OutputSink) -> _Child | None:
        server = self.fork_server
        assert server is not None
        env = request.env if request.env is not None else dict(os.environ)
        if not server.accepts(request.cmd, env, False):
            return None
        if request.cwd is not None and not os.path.isdir(request.cwd):
            return None  # exec reports the error as it always has
        loop = asyncio.get_running_loop()
        if self._fork_lock is None:
            self._fork_lock = asyncio.Lock()
        out_r, out_w = os.pipe()
        err_r, err_w = os.pipe()
        try:
            # Sent off the loop (a socket the server is not reading yet, during its imports, can fill up), one
            # at a time and in the launch's order; each is answered in turn, so the next request is sent
            # while the server forks this one. The first waits for the server's imports meanwhile; the loop
            # goes on starting the launch's other processes and hearing signals.
            async with self._fork_lock:
                answer = await loop.run_in_executor(None, server.submit, request.cmd, env, request.cwd, out_w, err_w)
        finally:
            _close(out_w)
            _close(err_w)
        pid = await asyncio.wrap_future(answer)
        if pid is None:
            _close(out_r)
            _close(err_r)
            return None
        child = _Child(
            pid=pid,
            name=request.name or "component",
            loop=loop,
            sink=sink,
            popen=None,
            complete=loop.create_future(),
            signal_group=self.signal_groups,
        )
        for fd, stream in ((out_r, "stdout"), (err_r, "stderr")):
            os.set_blocking(fd, False)
            child.readers[fd] = stream
            loop.add_reader(fd, child._read, fd)
        self._children.append(child)
        self._watch_exit(child)
        return child

    # ---- what a finished leader left behind ---------------------------------------------------------------------

    def _leader_exited(self, child: _Child) -> None:
        self._direct.discard(child.pid)
        if not _group_alive(child.pgid):
            self._forget(child.pgid)
            return
        self.logger.warning(f"[{child.name}] exited but left processes in its group; sending them SIGTERM")
        _killpg(child.pgid, signal.SIGTERM)
        started = child.loop.time()
        self._lingering[child.pgid] = child.name

        def check() -> None:
            if child.pgid not in self._lingering:
                return  # seen to by shutdown()
            if not _group_alive(child.pgid):
                self._gone(child.pgid)
            elif child.loop.time() - started >= self.linger_kill_s:
                self.logger.warning(
                    f"[{child.name}] its process group outlived SIGTERM by {self.linger_kill_s:g} s: SIGKILL"
                )
                _killpg(child.pgid, signal.SIGKILL)
                child.loop.call_later(LINGER_POLL_S, check)
            else:
                child.loop.call_later(LINGER_POLL_S, check)

        child.loop.call_later(LINGER_POLL_S, check)

    def _gone(self, pgid: int) -> None:
        name = self._lingering.pop(pgid, None)
        if name is not None:
            self.logger.info(f"[{name}] the rest of its process group is gone")
        self._forget(pgid)

    def _forget(self, pgid: int) -> None:
        if pgid in self._groups:
            self._groups.discard(pgid)
            self._tell_guard(f"-{pgid}")

    # ---- orphans -----------------------------------------------------------------------------------------------

    def _watch_orphans(self) -> None:
        """Reap, on every SIGCHLD, the grandchildren re-parented to the launcher (a child subreaper).

        A Python-level handler that hands the work to the loop: `loop.add_signal_handler` would take over the
        signal wakeup fd the LaunchService hears SIGINT through."""
        loop = asyncio.get_running_loop()
        if self._sigchld_loop is loop or self._prctl is None:
            return

        def on_sigchld(signum: int, frame: Any) -> None:
            # one look ORPHAN_LOOK_S after the first SIGCHLD, however many children ended meanwhile: 50 stopping
            # at once made 40-odd looks otherwise, each reading every thread's children list (an orphan's zombie
            # may wait that long; the end of the launch looks once more)
            if self._orphans_looked_for:
                self._orphans_looked_for = False
                with contextlib.suppress(RuntimeError):  # the loop is closed: the end of the launch reaps them
                    loop.call_soon_threadsafe(loop.call_later, ORPHAN_LOOK_S, self._reap_orphans_once)

        with contextlib.suppress(ValueError):  # not the main thread: orphans are reaped at the end
            self._previous_sigchld = signal.signal(signal.SIGCHLD, on_sigchld)
            self._sigchld_loop = loop

    def _reap_orphans_once(self) -> None:
        self._orphans_looked_for = True  # a SIGCHLD from now on asks for another look
        self.reap_orphans()

    def reap_orphans(self) -> None:
        keep = {c.pid for c in self._children if c.returncode is None}
        for extra in (self._guard.pid if self._guard is not None else None, self.fork_server and self.fork_server.pid):
            if extra:
                keep.add(extra)
        for path in glob.glob("/proc/self/task/*/children"):
            try:
                pids = [int(p) for p in Path(path).read_text().split()]
            except OSError:
                continue
            for pid in pids:
                if pid in keep:
                    continue
                try:
                    if os.getpgid(pid) in self._groups:
                        os.waitpid(pid, os.WNOHANG)
                except (ProcessLookupError, ChildProcessError, PermissionError):
                    pass

    # ---- the guard ---------------------------------------------------------------------------------------------

    def _tell_guard(self, line: str) -> None:
        """Queue a line for the guard: a new group once the loop's current turn is over, a group gone within
        GUARD_FORGET_S, the end at once. A write per group woke the guard each time (50 processes stopping:
        50 context switches, each a few ms on a loaded machine). A group the launcher dies before telling
        about still has its leader's death signal; one gone but not yet forgotten is no group to kill (its
        pgid is not reused that soon)."""
        if not self._guard_enabled:
            return
        self._guard_lines.append(line)
        try:
            loop = asyncio.get_running_loop()
        except RuntimeError:
            loop = None
        if loop is None or line == "exit":
            self._write_guard()
        elif line.startswith("+"):
            if not self._guard_write_soon:
                self._guard_write_soon = True
                loop.call_soon(self._write_guard)
        elif self._guard_write_later is None:
            self._guard_write_later = loop.call_later(GUARD_FORGET_S, self._write_guard)

    def _write_guard(self) -> None:
        self._guard_write_soon = False
        if self._guard_write_later is not None:
            self._guard_write_later.cancel()
            self._guard_write_later = None
        if not self._guard_lines:
            return
        lines, self._guard_lines = self._guard_lines, []
        if self._guard is None:
            self._guard = subprocess.Popen(
                [sys.executable, "-I", "-S", str(Path(__file__).with_name("guard.py"))],
                stdin=subprocess.PIPE,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
                start_new_session=True,
                close_fds=True,
            )
        assert self._guard.stdin is not None
        try:
            self._guard.stdin.write("".join(f"{line}\n" for line in lines).encode())
            self._guard.stdin.flush()
        except OSError:
            pass  # a dead guard must not take the launcher down; the death signal still covers direct children

    # ---- the end -----------------------------------------------------------------------------------------------

    async def shutdown(self) -> None:
        # What finished leaders left was sent SIGTERM already: the launch ends once it is gone (SIGKILL after
        # `linger_kill_s`), not with a second round of signals.
        deadline = time.monotonic() + self.linger_kill_s
        while self._lingering and time.monotonic() < deadline:
            await asyncio.sleep(LINGER_POLL_S)
            for pgid in [p for p in self._lingering if not _group_alive(p)]:
                self._gone(pgid)
        await super().shutdown()
        self.reap_orphans()
        for pgid in list(self._groups):
            if not _group_alive(pgid):
                self._forget(pgid)

    def launch_ending(self) -> None:
        """The launch shuts down, which starts nothing more: the fork server is killed now, so that its exit
        overlaps the processes' (`close` reaps it)."""
        if self.fork_server is not None:
            self.fork_server.kill()

    def close(self) -> None:
        """The launcher ends normally: end the fork server, release the guard without it killing anything."""
        if self._sigchld_loop is not None:
            with contextlib.suppress(ValueError, TypeError):
                signal.signal(signal.SIGCHLD, self._previous_sigchld or signal.SIG_DFL)
        self._sigchld_loop = None
        guard = self._guard
        if guard is not None:  # told first: it ends while the fork server is being ended
            self._tell_guard("exit")
            with contextlib.suppress(OSError):
                assert guard.stdin is not None
                guard.stdin.close()
        if self.fork_server is not None:
            self.fork_server.close(kill=True)  # every child is reaped by now: its imports need not finish
            self.fork_server = None
        if guard is not None:
            self._guard = None
            if not wait_exited(guard, 2.0):
                guard.kill()
                wait_exited(guard, 2.0)


def _death_signal_wrapper(launcher: int) -> list[str]:
    """`setpriv --pdeathsig KILL --`, or [] where setpriv, or its --pdeathsig, or /bin/sh is missing."""
    setpriv = shutil.which("setpriv")
    if setpriv is None or not os.access("/bin/sh", os.X_OK):
        return []
    wrapper = [setpriv, "--pdeathsig", "KILL", "--"]
    probe = [*wrapper, "/bin/sh", "-c", 'test "$PPID" = "$0"', str(launcher)]
    try:
        works = subprocess.run(probe, capture_output=True, timeout=10).returncode == 0
    except (OSError, subprocess.SubprocessError):
        works = False
    return wrapper if works else []


def _while_launcher_lives(wrapper: list[str], launcher: int, argv: list[str], env: Mapping[str, str]) -> list[str]:
    """`wrapper` running a shell line that execs `argv` only if `launcher` is still the parent. The shell would
    export PWD, set to the working directory: the command gets it as `env` has it, or not at all."""
    pwd = env.get("PWD")
    if pwd is None:
        line = ['test "$PPID" = "$0" && unset PWD && exec "$@"', str(launcher)]
    else:
        line = ['test "$PPID" = "$0" && PWD=$1 && shift && exec "$@"', str(launcher), pwd]
    return [*wrapper, "/bin/sh", "-c", *line, *argv]


def _check_executable(command: str, request: SpawnRequest) -> None:
    """Raise what exec would for `command` in the request's environment and working directory."""
    if os.sep in command:
        path = command if os.path.isabs(command) or request.cwd is None else os.path.join(request.cwd, command)
        if not os.path.exists(path):
            raise FileNotFoundError(errno.ENOENT, os.strerror(errno.ENOENT), command)
        if os.path.isdir(path) or not os.access(path, os.X_OK):
            raise PermissionError(errno.EACCES, os.strerror(errno.EACCES), command)
        return
    env = request.env if request.env is not None else os.environ
    if shutil.which(command, path=env.get("PATH", os.defpath)) is None:
        raise FileNotFoundError(errno.ENOENT, os.strerror(errno.ENOENT), command)


def _killpg(pgid: int, sig: int) -> None:
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(pgid, sig)
