"""The spawner interface and the POSIX spawner: process groups, pidfd exit watching, chunked output."""

from __future__ import annotations

import asyncio
import atexit
import logging
import os
import signal
import subprocess
import threading
import time
import weakref
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal, Protocol

_READ_SIZE = 65536


@dataclass(frozen=True)
class SpawnRequest:
    """What to run: the command (already substituted), where, with which environment.

    `shell` runs `' '.join(cmd)` with /bin/sh. `emulate_tty` gives the child a pseudo-terminal for stdout
    and one for stderr (so it line-buffers and colours as on a terminal). `stdin` is 'pipe' (an open pipe
    nothing is written to, as ros2/launch gives), 'inherit' (the launcher's), or 'devnull'.
    """

    cmd: list[str]
    cwd: str | None = None
    env: dict[str, str] | None = None
    shell: bool = False
    emulate_tty: bool = False
    stdin: Literal['pipe', 'inherit', 'devnull'] = 'pipe'
    name: str = ''


class OutputSink(Protocol):
    """Receives a child's output as it is read (chunks of bytes, not necessarily whole lines)."""

    def on_stdout(self, data: bytes) -> None: ...

    def on_stderr(self, data: bytes) -> None: ...


class ChildProcess(Protocol):
    """A started child. `complete` resolves to the exit code (-N for signal N) once the leader is reaped
    and what it wrote before exiting has been delivered; later output (from descendants still holding the
    pipes) is still delivered until `close()`."""

    pid: int
    pgid: int
    complete: asyncio.Future

    def get_pid(self) -> int: ...

    def get_returncode(self) -> int | None: ...

    def send_signal(self, sig: int) -> None: ...

    def kill(self) -> None: ...

    def terminate(self) -> None: ...

    def close(self) -> None: ...


class Spawner(Protocol):
    """Starts children for a launch and ends those still alive when it is over."""

    async def spawn(self, request: SpawnRequest, sink: OutputSink) -> ChildProcess: ...

    def signal_all(self, sig: int) -> None: ...

    async def shutdown(self) -> None: ...


def _group_alive(pgid: int) -> bool:
    """Whether a process of the group still runs (zombies, waiting for whoever reaps orphans, do not)."""
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    try:
        entries = os.listdir('/proc')
    except OSError:
        return True  # no /proc to tell zombies apart
    for entry in entries:
        if not entry.isdigit():
            continue
        try:
            with open(f'/proc/{entry}/stat', 'rb') as f:
                fields = f.read().rsplit(b')', 1)[1].split()
        except (OSError, IndexError):
            continue
        # fields: state, ppid, pgrp, ...
        if len(fields) > 2 and int(fields[2]) == pgid and fields[0] not in (b'Z', b'X'):
            return True
    return False


@dataclass(eq=False)
class _Child:
    """A child of the POSIX spawner (see `ChildProcess`)."""

    pid: int
    name: str
    loop: asyncio.AbstractEventLoop
    sink: OutputSink
    popen: subprocess.Popen | None  # None: forked by the fork server
    complete: asyncio.Future
    readers: dict[int, str] = field(default_factory=dict)  # fd -> 'stdout' | 'stderr'
    stdin_fd: int | None = None
    pidfd: int | None = None
    returncode: int | None = None
    closed: bool = False
    signal_group: bool = True
    on_leader_exit: Callable[[_Child], None] | None = None

    @property
    def pgid(self) -> int:
        return self.pid  # a session leader: its group is its pid

    def get_pid(self) -> int:
        return self.pid

    def get_returncode(self) -> int | None:
        return self.returncode

    def send_signal(self, sig: int) -> None:
        """Signal the child's process group, or the child alone (ProcessLookupError when it is gone)."""
        if self.signal_group:
            os.killpg(self.pgid, sig)
        elif self.returncode is None:
            os.kill(self.pid, sig)
        else:
            raise ProcessLookupError(self.pid)

    def kill(self) -> None:
        self.send_signal(signal.SIGKILL)

    def terminate(self) -> None:
        self.send_signal(signal.SIGTERM)

    def close(self) -> None:
        """Stop reading the child's output and release its pipes (the group is left as it is)."""
        if self.closed:
            return
        self.closed = True
        for fd in list(self.readers):
            self._stop_reading(fd)
        if self.stdin_fd is not None:
            _close(self.stdin_fd)
            self.stdin_fd = None

    # ---- output --------------------------------------------------------------------------------------------

    def _read(self, fd: int) -> bool:
        """Deliver what can be read from `fd` now; False at end of file."""
        while True:
            try:
                data = os.read(fd, _READ_SIZE)
            except BlockingIOError:
                return True
            except InterruptedError:
                continue
            except OSError:  # EIO: the pseudo-terminal's other side is closed
                data = b''
            if not data:
                self._stop_reading(fd)
                return False
            if self.readers.get(fd) == 'stdout':
                self.sink.on_stdout(data)
            else:
                self.sink.on_stderr(data)
            if len(data) < _READ_SIZE:
                return True

    def _stop_reading(self, fd: int) -> None:
        if self.readers.pop(fd, None) is not None:
            self.loop.remove_reader(fd)
            _close(fd)

    # ---- exit ----------------------------------------------------------------------------------------------

    def _on_pidfd(self) -> None:
        try:
            pid, status = os.waitpid(self.pid, os.WNOHANG)
        except ChildProcessError:
            pid, status = self.pid, 0  # reaped elsewhere: the status is lost
        if pid == 0:
            return
        self._exited(os.waitstatus_to_exitcode(status))

    def _exited(self, code: int) -> None:
        if self.pidfd is not None:
            self.loop.remove_reader(self.pidfd)
            _close(self.pidfd)
            self.pidfd = None
        self.returncode = code
        if self.popen is not None:
            self.popen.returncode = code  # Popen must not wait for it again
        for fd in list(self.readers):
            self._read(fd)  # what the child wrote before exiting comes before its exit
        if self.on_leader_exit is not None:
            self.on_leader_exit(self)
        if not self.complete.done():
            self.complete.set_result(code)


def _close(fd: int) -> None:
    try:
        os.close(fd)
    except OSError:
        pass


_spawners: weakref.WeakSet = weakref.WeakSet()


@atexit.register
def _kill_leftovers() -> None:
    """At interpreter exit, SIGKILL every group a spawner started that is still alive (a run cut short)."""
    for spawner in list(_spawners):
        spawner.kill_all()


class PosixSpawner:
    """Children in process groups of their own, watched on the asyncio loop.

    `signal_all` signals every live group (what a terminal's Ctrl-C would reach); `shutdown` ends the groups
    still alive after `term_timeout_s` with SIGKILL, logging each step. With `signal_groups=False` a child's
    signals (ShutdownProcess, SignalProcess, the escalation) reach the process only, as in ros2/launch; its
    group is still ended with the run.
    """

    def __init__(
        self, *, term_timeout_s: float = 2.0, logger: logging.Logger | None = None, signal_groups: bool = True
    ) -> None:
        self.term_timeout_s = term_timeout_s
        self.signal_groups = signal_groups
        self.logger = logger if logger is not None else logging.getLogger('launch.supervision')
        self._children: list[_Child] = []
        self.preexec_fn: Callable[[], None] | None = None  # run in each exec'd child before exec
        _spawners.add(self)

    async def spawn(self, request: SpawnRequest, sink: OutputSink) -> _Child:
        loop = asyncio.get_running_loop()
        argv = ['/bin/sh', '-c', ' '.join(request.cmd)] if request.shell else list(request.cmd)
        parent_ends: list[tuple[int, str]] = []
        child_ends: list[int] = []
        try:
            if request.emulate_tty:
                import pty

                out_master, out_slave = pty.openpty()
                err_master, err_slave = pty.openpty()
                parent_ends += [(out_master, 'stdout'), (err_master, 'stderr')]
                child_ends += [out_slave, err_slave]
                stdout, stderr = out_slave, err_slave
            else:
                out_r, out_w = os.pipe()
                err_r, err_w = os.pipe()
                parent_ends += [(out_r, 'stdout'), (err_r, 'stderr')]
                child_ends += [out_w, err_w]
                stdout, stderr = out_w, err_w
            stdin = {'pipe': subprocess.PIPE, 'inherit': None, 'devnull': subprocess.DEVNULL}[request.stdin]
            exec_argv, preexec = self._how_to_exec(argv, request)
            popen = subprocess.Popen(
                exec_argv, stdin=stdin, stdout=stdout, stderr=stderr, cwd=request.cwd, env=request.env,
                start_new_session=True, close_fds=True, preexec_fn=preexec)
        except BaseException:
            for fd, _ in parent_ends:
                _close(fd)
            raise
        finally:
            for fd in child_ends:
                _close(fd)
        child = _Child(pid=popen.pid, name=request.name or os.path.basename(argv[0]), loop=loop, sink=sink,
                       popen=popen, complete=loop.create_future(), signal_group=self.signal_groups)
        if popen.stdin is not None:
            child.stdin_fd = os.dup(popen.stdin.fileno())
            popen.stdin.close()
        for fd, stream in parent_ends:
            os.set_blocking(fd, False)
            child.readers[fd] = stream
            loop.add_reader(fd, child._read, fd)
        self._children.append(child)
        self._watch_exit(child)
        return child

    def _how_to_exec(self, argv: list[str], request: SpawnRequest) -> tuple[list[str], Callable[[], None] | None]:
        """What is exec'd for `argv`, and the function run in the child before (a subclass may wrap `argv`)."""
        return argv, self.preexec_fn

    def _watch_exit(self, child: _Child) -> None:
        try:
            child.pidfd = os.pidfd_open(child.pid)
        except (AttributeError, OSError):
            child.pidfd = None
        if child.pidfd is not None:
            # Readable once the child has exited, already gone included; never handled inside spawn(), where
            # its output would reach the launch before the caller has the child's pid.
            child.loop.add_reader(child.pidfd, child._on_pidfd)
            return
        # no pidfd (old kernel, other platform): a thread waits for it
        def wait() -> None:
            try:
                _, status = os.waitpid(child.pid, 0)
                code = os.waitstatus_to_exitcode(status)
            except ChildProcessError:
                code = 0
            try:
                child.loop.call_soon_threadsafe(child._exited, code)
            except RuntimeError:
                pass  # the loop is closed: nobody is waiting any more

        threading.Thread(target=wait, name=f'wait-{child.pid}', daemon=True).start()

    def kill_all(self) -> None:
        """SIGKILL every group still alive, now, without the loop (a run aborted, the interpreter exiting)."""
        for child in self._children:
            if _group_alive(child.pgid):
                self.logger.error(f"killing process group {child.pgid} of '{child.name}': the launch was aborted")
                _killpg(child.pgid, signal.SIGKILL)

    def live_groups(self) -> list[tuple[int, str]]:
        """(pgid, name) of the groups started here that still have a process."""
        return [(c.pgid, c.name) for c in self._children if _group_alive(c.pgid)]

    def signal_all(self, sig: int) -> None:
        """Send `sig` to every group still alive."""
        for child in self._children:
            _killpg(child.pgid, sig)

    async def shutdown(self) -> None:
        """End every group still alive: SIGTERM, then SIGKILL after `term_timeout_s`; release all pipes."""
        alive = self.live_groups()
        for pgid, name in alive:
            self.logger.warning(
                f"process group {pgid} of '{name}' still running as the launch ends: sending SIGTERM")
            _killpg(pgid, signal.SIGTERM)
        deadline = time.monotonic() + self.term_timeout_s
        while alive and time.monotonic() < deadline:
            await asyncio.sleep(0.02)
            alive = [(pgid, name) for pgid, name in alive if _group_alive(pgid)]
        for pgid, name in alive:
            self.logger.error(
                f"process group {pgid} of '{name}' still running {self.term_timeout_s} s after SIGTERM: "
                'sending SIGKILL')
            _killpg(pgid, signal.SIGKILL)
        for child in self._children:
            if child.returncode is None:
                await asyncio.wait([child.complete], timeout=self.term_timeout_s)
            child.close()
        self._children = [c for c in self._children if c.returncode is None]


def _killpg(pgid: int, sig: int) -> None:
    try:
        os.killpg(pgid, sig)
    except (ProcessLookupError, PermissionError):
        pass
