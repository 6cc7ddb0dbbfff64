"""The real event loop: child pipes, signals and timers feeding the supervisor, on the main thread.

Signals arrive through a wake-up pipe (signal.set_wakeup_fd), so a Ctrl-C or a child's exit is handled
between two steps of the loop, never in the middle of one; output is read as it comes, line by line.
"""

from __future__ import annotations

import contextlib
import os
import selectors
import signal
import sys
from dataclasses import dataclass, field
from typing import IO

from diffctl.launch_legacy import fork_server
from diffctl.launch_legacy.spawner import PosixSpawner
from diffctl.launch_legacy.supervisor import Supervisor

HANDLED_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGUSR1, signal.SIGCHLD)
MAX_LINE = 64 * 1024


@dataclass
class _Pipe:
    name: str
    pid: int
    stream: str
    file: IO[bytes]
    pending: bytes = field(default=b"")


class EventLoop:
    def __init__(
        self,
        *,
        watch_stdin: bool = True,
        fork_env: dict[str, str] | None = None,
        server: fork_server.ForkServer | None = None,
        preload: fork_server.Preload | None = None,
    ) -> None:
        """fork_env: start the fork server now (its imports overlap whatever the caller does next), in the
        environment of a child that sets nothing of its own; server: one the caller started already."""
        self.selector = selectors.DefaultSelector()
        self.spawner = PosixSpawner(on_pipes=self._add_pipes)
        if server is not None:
            self.spawner.fork_server = server
        elif fork_env is not None and fork_server.enabled(fork_env):
            self.spawner.fork_server = fork_server.ForkServer(fork_env, preexec=self.spawner.preexec, preload=preload)
        self.supervisor: Supervisor | None = None
        self._pipes: dict[int, list[_Pipe]] = {}
        self._wake_r, self._wake_w = os.pipe()
        os.set_blocking(self._wake_r, False)
        os.set_blocking(self._wake_w, False)
        self.selector.register(self._wake_r, selectors.EVENT_READ, "wake")
        self._stdin = watch_stdin and sys.stdin is not None and sys.stdin.isatty()

    # ---- pipes -------------------------------------------------------------------------------------------------

    def _add_pipes(self, name: str, pid: int, stdout: IO[bytes], stderr: IO[bytes]) -> None:
        pipes = [_Pipe(name, pid, "stdout", stdout), _Pipe(name, pid, "stderr", stderr)]
        for p in pipes:
            os.set_blocking(p.file.fileno(), False)
            self.selector.register(p.file, selectors.EVENT_READ, p)
        self._pipes[pid] = pipes

    def _read(self, p: _Pipe) -> str:
        """Read what is there: "data", "again" (nothing now) or "eof" (the pipe is then closed)."""
        try:
            data = os.read(p.file.fileno(), 65536)
        except BlockingIOError:
            return "again"
        except OSError:
            data = b""
        if not data:
            if p.pending:
                self._emit(p, p.pending)
                p.pending = b""
            self.selector.unregister(p.file)
            p.file.close()
            pipes = self._pipes.get(p.pid, [])
            if p in pipes:
                pipes.remove(p)
            return "eof"
        p.pending += data
        *lines, p.pending = p.pending.split(b"\n")
        for line in lines:
            self._emit(p, line)
        if len(p.pending) > MAX_LINE:
            self._emit(p, p.pending)
            p.pending = b""
        return "data"

    def _emit(self, p: _Pipe, raw: bytes) -> None:
        assert self.supervisor is not None
        self.supervisor.on_line(p.name, p.stream, raw.rstrip(b"\r").decode("utf-8", errors="replace"))

    def _drain(self, pid: int) -> None:
        # The last lines a process printed come before the news of its exit (bounded: a process left in
        # the group may hold the pipe open and keep writing).
        for p in list(self._pipes.get(pid, [])):
            for _ in range(64):
                if self._read(p) != "data":
                    break

    def wake(self) -> None:
        """Wake the loop from another thread."""
        with contextlib.suppress(BlockingIOError, OSError):
            os.write(self._wake_w, b"\0")

    # ---- running -----------------------------------------------------------------------------------------------

    def run(self, supervisor: Supervisor) -> int:
        self.supervisor = supervisor
        supervisor.notify = self.wake  # work posted from other threads (bus callbacks) wakes the loop
        previous = {sig: signal.signal(sig, lambda *_: None) for sig in HANDLED_SIGNALS}
        old_wakeup = signal.set_wakeup_fd(self._wake_w, warn_on_full_buffer=False)
        if self._stdin and not any(s.spec.interactive for s in supervisor.states.values()):
            self.selector.register(sys.stdin.fileno(), selectors.EVENT_READ, "stdin")
        try:
            supervisor.start()
            self._reap(orphans=False)
            while not supervisor.done:
                deadline = supervisor.next_deadline()
                timeout = 1.0 if deadline is None else min(1.0, max(0.0, deadline - supervisor.now()))
                signals: list[int] = []
                for key, _ in self.selector.select(timeout):
                    if key.data == "wake":
                        signals += self._signals()
                    elif key.data == "stdin":
                        self._stdin_line()
                    else:
                        self._read(key.data)
                chld = signal.SIGCHLD in signals
                for sig in signals:
                    if sig not in (0, signal.SIGCHLD):  # 0: a wake-up from another thread (bus probes)
                        supervisor.on_signal(sig)
                self._reap(orphans=chld)
                supervisor.tick()
            return supervisor.exit_code
        except BaseException:
            # The launcher itself failed (a bug, a broken pipe): no child may outlive it.
            self.spawner.kill_all()
            raise
        finally:
            supervisor.close()
            signal.set_wakeup_fd(old_wakeup)
            for sig, handler in previous.items():
                signal.signal(sig, handler)
            self._close()

    def _signals(self) -> list[int]:
        out: list[int] = []
        with contextlib.suppress(BlockingIOError):
            while True:
                data = os.read(self._wake_r, 512)
                if not data:
                    break
                out += list(data)
        return out

    def _stdin_line(self) -> None:
        assert self.supervisor is not None
        try:
            data = os.read(sys.stdin.fileno(), 1024)
        except OSError:
            data = b""
        if not data:
            self.selector.unregister(sys.stdin.fileno())
            return
        self.supervisor.show_status()

    def _reap(self, *, orphans: bool) -> None:
        assert self.supervisor is not None
        for pid, code in self.spawner.reap(orphans=orphans):
            self._drain(pid)
            self.supervisor.on_exit(pid, code)

    def _close(self) -> None:
        for pipes in self._pipes.values():
            for p in pipes:
                with contextlib.suppress(KeyError, ValueError, OSError):
                    self.selector.unregister(p.file)
                p.file.close()
        self._pipes.clear()
        self.spawner.close()
        self.selector.close()
        os.close(self._wake_r)
        os.close(self._wake_w)
