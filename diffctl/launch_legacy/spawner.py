"""Starting real processes so that none outlives the launcher.

- every child gets its own session (so its own process group), and PR_SET_PDEATHSIG=SIGKILL: it dies
  with the launcher even when the launcher is SIGKILLed;
- the launcher is a child subreaper (PR_SET_CHILD_SUBREAPER): orphaned grandchildren are re-parented to
  it and reaped here, not by init;
- the guard process (guard.py) SIGKILLs every known group if the launcher dies, which catches grandchildren
  that PDEATHSIG does not reach.

diffctl's own components are forked from the fork server (fork_server.py) when one is given: the same
session, death signal, pipes, argv and environment, without paying the interpreter's imports again.
"""

from __future__ import annotations

import ctypes
import glob
import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import IO

from diffctl.launch_legacy.fork_server import ForkServer
from diffctl.launch_legacy.process_state import Child

PR_SET_PDEATHSIG = 1
PR_SET_CHILD_SUBREAPER = 36

PipesListener = Callable[[str, int, IO[bytes], IO[bytes]], None]


def _libc() -> ctypes.CDLL | None:
    try:
        return ctypes.CDLL(None, use_errno=True)
    except OSError:
        return None


class PosixSpawner:
    def __init__(
        self, on_pipes: PipesListener | None = None, *, guard: bool = True, fork_server: ForkServer | None = None
    ) -> None:
        self.on_pipes = on_pipes
        self.fork_server = fork_server
        self._libc = _libc()
        self._prctl = self._libc.prctl if self._libc is not None and sys.platform.startswith("linux") else None
        self._parent = os.getpid()
        self._children: dict[int, subprocess.Popen[bytes] | None] = {}  # None: forked by the fork server
        self._groups: set[int] = set()
        self._guard_enabled = guard
        self._guard: subprocess.Popen[bytes] | None = None
        if self._prctl is not None:
            self._prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0)

    # ---- the guard ---------------------------------------------------------------------------------------------

    def _tell_guard(self, line: str) -> None:
        if not self._guard_enabled:
            return
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
            self._guard.stdin.write(line.encode() + b"\n")
            self._guard.stdin.flush()
        except OSError:
            pass  # a dead guard must not take the launcher down; PDEATHSIG still covers direct children

    # ---- children ----------------------------------------------------------------------------------------------

    def preexec(self) -> None:
        # Runs in the child between fork and exec: keep it to the prctl and the race check.
        if self._prctl is not None:
            self._prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
            if os.getppid() != self._parent:
                os._exit(1)  # the launcher died before the death signal was armed

    def spawn(self, name: str, argv: list[str], env: dict[str, str], cwd: str | None, interactive: bool) -> Child:
        if self.fork_server is not None and self.fork_server.accepts(argv, env, interactive):
            pid = self._fork(name, argv, env, cwd)
            if pid is not None:
                return Child(pid, pid)
        proc = subprocess.Popen(
            argv,
            stdin=None if interactive else subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            env=env,
            cwd=cwd,
            start_new_session=True,
            preexec_fn=self.preexec,
            close_fds=True,
            bufsize=0,
        )
        self._children[proc.pid] = proc
        self._groups.add(proc.pid)
        self._tell_guard(f"+{proc.pid}")
        if self.on_pipes is not None and proc.stdout is not None and proc.stderr is not None:
            self.on_pipes(name, proc.pid, proc.stdout, proc.stderr)
        return Child(proc.pid, proc.pid)

    def _fork(self, name: str, argv: list[str], env: dict[str, str], cwd: str | None) -> int | None:
        assert self.fork_server is not None
        if cwd is not None and not os.path.isdir(cwd):
            return None  # exec reports the error as it always has
        out_r, out_w = os.pipe()
        err_r, err_w = os.pipe()
        try:
            pid = self.fork_server.spawn(argv, env, cwd, out_w, err_w)
        finally:
            os.close(out_w)
            os.close(err_w)
        if pid is None:
            os.close(out_r)
            os.close(err_r)
            return None
        self._children[pid] = None
        self._groups.add(pid)
        self._tell_guard(f"+{pid}")
        stdout, stderr = os.fdopen(out_r, "rb", buffering=0), os.fdopen(err_r, "rb", buffering=0)
        if self.on_pipes is not None:
            self.on_pipes(name, pid, stdout, stderr)
        else:
            stdout.close()
            stderr.close()
        return pid

    def signal_group(self, child: Child, sig: int) -> bool:
        try:
            os.killpg(child.pgid, sig)
            return True
        except (ProcessLookupError, PermissionError):
            return False

    def signal_process(self, child: Child, sig: int) -> bool:
        """The process itself, not its group (`--signal process`, as ros2 launch signals)."""
        try:
            os.kill(child.pid, sig)
            return True
        except (ProcessLookupError, PermissionError):
            return False

    def group_alive(self, child: Child) -> bool:
        return self.signal_group(child, 0)

    def forget(self, child: Child) -> None:
        if child.pgid in self._groups:
            self._groups.discard(child.pgid)
            self._tell_guard(f"-{child.pgid}")

    def reap(self, *, orphans: bool = True) -> list[tuple[int, int]]:
        """(pid, exit code) of children that ended; also reaps orphaned grandchildren of our groups."""
        ended: list[tuple[int, int]] = []
        for pid, proc in list(self._children.items()):
            try:
                done, status = os.waitpid(pid, os.WNOHANG)
            except ChildProcessError:
                done, status = pid, 0
            if done:
                code = os.waitstatus_to_exitcode(status)
                if proc is not None:
                    proc.returncode = code
                del self._children[pid]
                ended.append((pid, code))
        if orphans:
            self._reap_orphans()
        return ended

    def _reap_orphans(self) -> None:
        for path in glob.glob("/proc/self/task/*/children"):
            try:
                pids = [int(p) for p in Path(path).read_text().split()]
            except OSError:
                continue
            for pid in pids:
                if pid in self._children or (self._guard is not None and pid == self._guard.pid):
                    continue
                if self.fork_server is not None and pid == self.fork_server.pid:
                    continue
                try:
                    if os.getpgid(pid) in self._groups:
                        os.waitpid(pid, os.WNOHANG)
                except (ProcessLookupError, ChildProcessError):
                    pass

    def kill_all(self, wait_s: float = 1.0) -> None:
        """Last resort when the launcher itself fails: SIGKILL every group and reap what we can."""
        for pgid in list(self._groups):
            try:
                os.killpg(pgid, signal.SIGKILL)
            except OSError:
                pass
        deadline = time.monotonic() + wait_s
        while self._children and time.monotonic() < deadline:
            self.reap()
            time.sleep(0.01)
        for child_pid in list(self._groups):
            self.forget(Child(child_pid, child_pid))

    def drop_fork_server(self) -> None:
        """No process will be forked: stop the fork server at once, its imports unfinished."""
        if self.fork_server is not None:
            self.fork_server.close(kill=True)
            self.fork_server = None

    def close(self, *, kill_fork_server: bool = False) -> None:
        """The launcher ends normally: end the fork server, release the guard without it killing anything."""
        if self.fork_server is not None:
            self.fork_server.close(kill=kill_fork_server)
        if self._guard is not None:
            self._tell_guard("exit")
            try:
                assert self._guard.stdin is not None
                self._guard.stdin.close()
                self._guard.wait(timeout=2.0)
            except (OSError, subprocess.TimeoutExpired):
                self._guard.kill()
            self._guard = None
