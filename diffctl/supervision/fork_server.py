"""The launcher's side of the fork server: start the zygote, ask it for diffctl components, fall back to exec.

Every diffctl component is `python -m diffctl …`, and most of its start-up is importing the same modules
(numpy, pybullet, zenoh, rosbags, lxml, diffctl's own). The zygote (zygote.py) imports them once, before any
Zenoh session or thread exists, and forks each component from that state. The zygote runs in the
environment the launcher gives a process that sets nothing of its own, and only commands that exec would
start identically are forked: `<this python> -m diffctl …`, not interactive, with that environment (so a
forked component's interpreter settings, PYTHON*, LD_*, and its /proc/PID/environ are what exec would have
given it), give or take Gazebo's search paths (CALL_TIME_PREFIXES): launch files set those for the processes
after them (ros_gz_sim's gz_sim.launch.py appends GZ_SIM_RESOURCE_PATH) and diffctl reads them only when it
needs them, so the component gets them in its os.environ (/proc/PID/environ shows the zygote's). Everything
else, and every request the zygote cannot answer, is exec'd as before. DIFFCTL_FORK_SERVER=0 turns the
server off.
"""

from __future__ import annotations

import collections
import contextlib
import ctypes
import json
import os
import signal
import socket
import subprocess
import sys
import threading
from collections.abc import Callable, Mapping, Sequence

from diffctl.supervision.exit_wait import wait_exited
from diffctl.supervision.zygote import MAX_MESSAGE, PR_SET_PDEATHSIG, TITLE_ROOM, Preload

# typing and concurrent.futures are imported by nothing else before the zygote's exec (this module is): 20 ms
TYPE_CHECKING = False
if TYPE_CHECKING:
    from concurrent.futures import Future

ENABLE_ENV = "DIFFCTL_FORK_SERVER"
REPLY_TIMEOUT_S = 60.0  # the first request waits for the zygote's imports, on a loaded machine too
# Environment variables diffctl reads only when it needs them (never at import or in a warm-up), so a process
# forked from a zygote that lacks them behaves as one exec'd with them: Gazebo's resource and plugin paths.
CALL_TIME_PREFIXES = ("GZ_", "IGN_", "GAZEBO_", "SDF_PATH")


def enabled(env: Mapping[str, str]) -> bool:
    return env.get(ENABLE_ENV, "1").strip().lower() not in ("0", "false", "no", "off")


def is_component(argv: Sequence[str]) -> bool:
    """`<this interpreter> -m diffctl …`: the command line of every diffctl component the launcher starts."""
    return (
        len(argv) >= 3
        and os.path.abspath(argv[0]) == os.path.abspath(sys.executable)
        and list(argv[1:3]) == ["-m", "diffctl"]
    )


def same_start(env: Mapping[str, str], zygote_env: Mapping[str, str]) -> bool:
    """Whether a process exec'd in `env` starts as one forked from a zygote started in `zygote_env` and given
    `env` after the fork: they differ at most in variables read only at call time."""
    if env == zygote_env:
        return True
    keys = set(env) | set(zygote_env)
    return all(env.get(k) == zygote_env.get(k) or k.startswith(CALL_TIME_PREFIXES) for k in keys)


def dies_with_launcher() -> Callable[[], None] | None:
    """A preexec_fn arming PR_SET_PDEATHSIG=SIGKILL, for a fork server started before the launcher's spawner
    exists (which arms the same for every child it execs); None off Linux."""
    if not sys.platform.startswith("linux"):
        return None
    try:
        prctl = ctypes.CDLL(None, use_errno=True).prctl
    except OSError:
        return None
    parent = os.getpid()

    def preexec() -> None:
        prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
        if os.getppid() != parent:
            os._exit(1)  # the launcher died before the death signal was armed

    return preexec


class ForkServer:
    """One zygote per launch; `spawn` returns the component's pid, or None when it must be exec'd instead."""

    def __init__(
        self, env: Mapping[str, str], preexec: Callable[[], None] | None = None, preload: Preload | None = None
    ) -> None:
        """env: what the launcher gives a child that sets no variables of its own; preload: what the server
        imports and warms up ahead (the CLI layer's list: the engine names no component)."""
        self._env = dict(env)
        ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        try:
            self.process: subprocess.Popen[bytes] | None = subprocess.Popen(
                [
                    sys.executable,
                    "-m",
                    "diffctl.supervision.zygote",
                    str(theirs.fileno()),
                    (preload or Preload()).to_json(),
                    " " * TITLE_ROOM,
                ],
                stdin=subprocess.DEVNULL,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
                env=self._env,
                pass_fds=(theirs.fileno(),),
                start_new_session=True,
                preexec_fn=preexec,
            )
        finally:
            theirs.close()
        self._sock: socket.socket | None = ours
        ours.settimeout(REPLY_TIMEOUT_S)
        self._answering()

    def _answering(self) -> None:
        # Requests are answered in the order they were sent, so one may be sent before the last is answered:
        # the zygote then goes from one fork to the next without waiting for the launcher's next request.
        self._lock = threading.Lock()
        self._waiting: collections.deque[Future[int | None]] = collections.deque()
        self._replies: threading.Thread | None = None

    @property
    def pid(self) -> int | None:
        return self.process.pid if self.process is not None else None

    def accepts(self, argv: list[str], env: Mapping[str, str], interactive: bool) -> bool:
        if self._sock is None or interactive or not is_component(argv):
            return False
        return same_start(env, self._env)

    def spawn(
        self, argv: list[str], env: Mapping[str, str], cwd: str | None, stdout_w: int, stderr_w: int
    ) -> int | None:
        """Fork `argv` from the zygote with these pipe ends as its stdout and stderr; None: exec it instead."""
        return self.submit(argv, env, cwd, stdout_w, stderr_w).result()

    def submit(
        self, argv: list[str], env: Mapping[str, str], cwd: str | None, stdout_w: int, stderr_w: int
    ) -> Future[int | None]:
        """Send the request now (the pipe ends may be closed once this returns); the future gets the pid, or
        None when the component must be exec'd instead. Sent requests are answered in order."""
        from concurrent.futures import Future

        answer: Future[int | None] = Future()
        message = json.dumps({"argv": argv, "env": dict(env), "cwd": cwd}).encode()
        with self._lock:
            sock = self._sock
            if sock is None or len(message) > MAX_MESSAGE:
                answer.set_result(None)
                return answer
            try:
                socket.send_fds(sock, [message], [stdout_w, stderr_w])
            except OSError:
                answer.set_result(None)
                broken = True
            else:
                self._waiting.append(answer)
                broken = False
                if self._replies is None:
                    self._replies = threading.Thread(
                        target=self._read_replies, args=(sock,), name="fork-server-replies", daemon=True
                    )
                    self._replies.start()
        if broken:
            self.close()  # a zygote that does not answer serves nobody: exec from now on
        return answer

    def _read_replies(self, sock: socket.socket) -> None:
        while True:
            try:
                data = sock.recv(4096)
            except TimeoutError:
                with self._lock:
                    if not self._waiting:
                        continue  # nothing asked: quiet is no failure
                data = b""
            except OSError:
                data = b""
            if not data:
                break
            try:
                pid = json.loads(data).get("pid")
            except (ValueError, AttributeError):
                pid = None
            with self._lock:
                answer = self._waiting.popleft() if self._waiting else None
            if answer is not None:
                _answer(answer, pid if isinstance(pid, int) and not isinstance(pid, bool) and pid > 0 else None)
        with self._lock:
            unanswered, self._waiting = list(self._waiting), collections.deque()
            stopped = self._sock is not sock  # closed by the launcher, not lost
        for answer in unanswered:
            _answer(answer, None)
        if not stopped:
            self.close()  # a zygote that does not answer serves nobody: exec from now on

    def kill(self) -> None:
        """SIGKILL the zygote now without waiting for it (`close` reaps it): a launch that is ending forks nothing
        more, and the zygote's exit then overlaps the stopping of the launch's processes. A request under way
        gets no pid, and is exec'd."""
        process = self.process
        if process is not None:
            process.kill()

    def close(self, *, kill: bool = False) -> None:
        """Closing our end ends the zygote once it has imported everything (its children are the launcher's,
        not its own); kill=True ends it now."""
        with self._lock:
            sock, self._sock = self._sock, None
            process, self.process = self.process, None
        if sock is not None:
            with contextlib.suppress(OSError):
                sock.shutdown(socket.SHUT_RDWR)  # wakes the thread reading the replies
            sock.close()
        if process is not None:
            if kill:
                process.kill()
            if not wait_exited(process, 2.0):
                process.kill()
                wait_exited(process, 2.0)


def _answer(answer: Future[int | None], pid: int | None) -> None:
    if answer.set_running_or_notify_cancel():  # a launch that stopped waiting has cancelled it
        answer.set_result(pid)
