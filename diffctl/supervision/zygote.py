"""The fork server process (zygote): import diffctl's heavy modules once, then fork components from it.

Started by the launcher (fork_server.py) as `python -m diffctl.supervision.zygote FD ROOM` with one end of a socket
pair as FD, in exactly the environment the launcher gives its children (so /proc/PID/environ of a forked
component is what an exec'd one would show) and ROOM, blank space in argv that a component's command line
is written over (so ps, pgrep and psutil show `python -m diffctl sim run …`, not the zygote).
It imports numpy, pybullet, zenoh, rosbags, lxml and diffctl's component modules while it is still the only
thread of a process that has opened no Zenoh session, then serves requests: argv, environment and working
directory, with the child's stdout and stderr pipe ends passed as file descriptors. For each it makes a
child of the launcher (clone's CLONE_PARENT, or forking twice so that the component is re-parented to the
launcher, a child subreaper), and the launcher waits for it, signals its group and reaps it exactly as a
process it had started itself. The component then takes its own
session, arms PR_SET_PDEATHSIG once the launcher is its parent, puts its pipes on fds 1 and 2, closes every
other descriptor, takes the requested environment and working directory, and runs `python -m diffctl`'s
main as the interpreter would — uncaught exceptions, SystemExit, KeyboardInterrupt and atexit included.
"""

from __future__ import annotations

import collections
import contextlib
import ctypes
import gc
import importlib
import json
import os
import runpy
import select
import signal
import socket
import sys
import time
import types
from collections.abc import Iterator

TITLE_ROOM = 4096  # bytes of argv a component's command line may take in ps
MAX_MESSAGE = 1 << 20
PR_SET_PDEATHSIG = 1
# what the launcher stops a component with (SIGKILL aside): blocked from the fork until `become` can take them
STOP_SIGNALS = frozenset({signal.SIGINT, signal.SIGTERM})


class Preload:
    """What the server imports before it serves (`modules`), what it imports while idle (`later`), and the
    warm-up functions (`module:function`) it calls after the imports. The launch core names no component:
    the list comes from the CLI layer (diffctl/cli/fork_preload.py), each component naming its own.

    A plain class, as Request below: the launcher imports this module before it starts the server, and
    dataclasses (15-20 ms) would delay that start."""

    __slots__ = ("later", "modules", "warm")

    def __init__(self, modules: tuple[str, ...] = (), later: tuple[str, ...] = (), warm: tuple[str, ...] = ()) -> None:
        self.modules = tuple(modules)
        self.later = tuple(later)
        self.warm = tuple(warm)

    def to_json(self) -> str:
        return json.dumps({"modules": self.modules, "later": self.later, "warm": self.warm})

    @classmethod
    def from_json(cls, text: str) -> Preload:
        if not text.strip():
            return cls()
        raw = json.loads(text)
        return cls(tuple(raw.get("modules", ())), tuple(raw.get("later", ())), tuple(raw.get("warm", ())))


# The later imports wait for this much quiet: a launch asks for its first components in a burst, a few ms
# apart, then for those chained on an exit (sim_control's second spawner, when the first exits: 0.4-0.6 s
# later under load), and a request that comes during an import waits for it: after 0.3 s of quiet, the
# visualizer's imports held the second spawner 0.1-0.2 s (its controller active 0.18 s later, load 9).
LATER_QUIET_S = 1.0


class Request:
    """A component to fork: its argv, environment, working directory and the pipe ends for stdout and stderr."""

    __slots__ = ("argv", "cwd", "env", "stderr_fd", "stdout_fd")

    def __init__(self, argv: list[str], env: dict[str, str], cwd: str | None, stdout_fd: int, stderr_fd: int) -> None:
        self.argv = argv
        self.env = env
        self.cwd = cwd
        self.stdout_fd = stdout_fd
        self.stderr_fd = stderr_fd


def preload(spec: Preload) -> None:
    # OpenBLAS starts a worker thread when numpy loads; a single-threaded BLAS keeps this process at one
    # thread, so fork() copies no lock another thread holds. Components get their own environment back.
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    # No collection while importing: what the imports allocate stays for good (frozen below), and the
    # collections the allocations would trigger cost 15-35 ms of the first component's wait.
    gc.disable()
    with dataclass_methods_cached():
        for name in spec.modules:
            _import(name)
        for target in spec.warm:
            with contextlib.suppress(Exception):
                module, _, function = target.partition(":")
                getattr(importlib.import_module(module), function)()
    # What is imported now lives as long as every component: out of the collector's sight, a component's
    # collections (and its final one at exit, which otherwise walks every module object for a good part of a
    # second on a busy machine) skip it, and its pages stay shared instead of being dirtied by the scans.
    # Frozen without a collection first: that full collection costs 35-45 ms of the first component's wait
    # and finds some 26 unreachable objects (kept for good, frozen); the later freeze collects.
    gc.freeze()
    gc.enable()
    if sys.platform.startswith("linux"):
        # pybullet prints its build time with C stdio: flush it here, or every component would print it again
        # when its copy of the buffer is flushed at exit.
        ctypes.CDLL(None).fflush(None)


def _import(name: str) -> None:
    with contextlib.suppress(Exception):
        importlib.import_module(name)


@contextlib.contextmanager
def dataclass_methods_cached() -> Iterator[None]:
    """Meanwhile, the methods `dataclasses` writes for a class are compiled once per machine, not once per run.

    It writes each (__init__, __repr__, __eq__, a frozen class's __setattr__ …) as source text and compiles it
    with the `exec` its module's globals resolve: the preload's 160 classes are 770 functions, some 120 ms of
    compiling, a fifth of the preload and all of it before the first component. Here that name is a function
    taking the code from a cache keyed by the text (the same text compiles to the same code: no inherited
    future flags, file name "<string>", as exec compiles a string), one marshalled file read once.
    The file maps each text to its code marshalled on its own, unmarshalled when a class asks for it: the
    cache holds the texts of every version of the code run on the machine (1,400 here, ~770 used), and
    unmarshalling them all cost 10 ms of the server's start, 35 ms at the 5,000 it may grow to."""
    import dataclasses
    import marshal

    path = _cache_file(CODE_CACHE_FILE)
    try:
        with open(path, "rb") as f:
            known = marshal.load(f)
    except (OSError, ValueError, EOFError, TypeError):
        known = {}
    if not isinstance(known, dict):
        known = {}
    new: dict[str, bytes] = {}

    def cached_exec(source: object, namespace: dict | None = None, local: object = None, /) -> None:
        if namespace is None:
            namespace = sys._getframe(1).f_globals  # as exec takes its caller's
        if isinstance(source, str):
            source = _cached_code(source, known, new)
        exec(source, namespace, local)  # the builtin, given the code dataclasses would have compiled

    dataclasses.exec = cached_exec  # type: ignore[attr-defined]
    try:
        yield
    finally:
        with contextlib.suppress(AttributeError):
            del dataclasses.exec  # type: ignore[attr-defined]
        if new:
            # a cache that outgrew what preloads use (code changed over time) starts again from this run's
            keep = {**known, **new} if len(known) + len(new) <= CODE_CACHE_ENTRIES else new
            _write_whole(path, marshal.dumps(keep))


CODE_CACHE_ENTRIES = 5000
# text -> marshalled code; named apart from the older layout's file (text -> code), which an older diffctl
# on the same machine still reads and writes
CODE_CACHE_FILE = "dataclass-methods-by-text.marshal"


def _cached_code(source: str, known: dict[str, object], new: dict[str, bytes]) -> types.CodeType:
    """The code of `source`: from the cache, else compiled and noted in `new`."""
    import marshal

    entry = known.get(source) or new.get(source)
    if isinstance(entry, bytes):
        try:
            code = marshal.loads(entry)
        except (ValueError, EOFError, TypeError):
            code = None
        if isinstance(code, types.CodeType):
            return code
    code = compile(source, "<string>", "exec", dont_inherit=True)
    new[source] = marshal.dumps(code)
    return code


def _cache_file(name: str) -> str:
    from importlib.util import MAGIC_NUMBER

    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "diffctl", f"bytecode-{MAGIC_NUMBER.hex()}", name)


def _write_whole(path: str, data: bytes) -> None:
    """Written whole or not at all: zygotes started together race to write the same file."""
    tmp = f"{path}.{os.getpid()}.tmp"
    try:
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(tmp, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except OSError:
        with contextlib.suppress(OSError):
            os.unlink(tmp)


def _freeze() -> None:
    gc.collect()
    gc.freeze()


class _Starting:
    """A request's answer in the making, kept in request order: a component's pid is read from its report pipe
    (and an intermediate, if any, reaped) while the server goes on to the next request."""

    __slots__ = ("answer", "middle", "report", "text")

    def __init__(self, report: int | None = None, middle: int | None = None,
                 answer: dict[str, object] | None = None) -> None:
        self.report = report
        self.middle = middle
        self.answer = answer
        self.text = b""

    def read(self) -> None:
        assert self.report is not None
        chunk = os.read(self.report, 64)
        if chunk:
            self.text += chunk
            return
        os.close(self.report)  # the component wrote its pid and closed its end, or died first
        self.report = None
        if self.middle is not None:
            os.waitpid(self.middle, 0)
        try:
            self.answer = {"pid": int(self.text)}
        except ValueError:
            self.answer = {"error": "fork failed in the intermediate process"}


def serve(sock: socket.socket, launcher_pid: int, later_modules: tuple[str, ...] = ()) -> Request | None:
    """Answer requests until the launcher closes its end (None); in a forked component, its Request.

    Answers go out in the order of the requests; the next request is taken as soon as a component is started,
    not once it has reported its pid (it must first be scheduled, which on a busy machine held the next fork
    back)."""
    later = list(later_modules)
    last_request = time.monotonic()
    starting: collections.deque[_Starting] = collections.deque()
    while True:
        while starting and starting[0].answer is not None:
            _reply(sock, starting.popleft().answer)  # type: ignore[arg-type]
        if later and not starting:
            quiet = time.monotonic() - last_request
            if not select.select([sock], [], [], max(0.0, LATER_QUIET_S - quiet))[0]:
                if time.monotonic() - last_request >= LATER_QUIET_S:
                    _import(later.pop(0))  # nothing asked for a while: one more of the later components
                    if not later:
                        _freeze()
                continue
        reports = {s.report: s for s in starting if s.report is not None}
        ready = select.select([sock, *reports], [], [])[0]
        for fd in ready:
            if fd in reports:
                reports[fd].read()
        if sock not in ready:
            continue
        last_request = time.monotonic()
        try:
            data, fds, _, _ = socket.recv_fds(sock, MAX_MESSAGE, 2)
        except (OSError, ValueError):
            return None
        if not data:
            return None
        try:
            message = json.loads(data)
            if len(fds) != 2:
                raise ValueError("expected the stdout and stderr descriptors")
            request = Request(message["argv"], message["env"], message.get("cwd"), fds[0], fds[1])
        except (ValueError, KeyError, TypeError) as e:
            for fd in fds:
                os.close(fd)
            starting.append(_Starting(answer={"error": f"bad request: {e}"}))
            continue
        child = _start_child(sock, request, launcher_pid)
        if isinstance(child, Request):
            return child
        os.close(request.stdout_fd)
        os.close(request.stderr_fd)
        starting.append(child)


def _reply(sock: socket.socket, message: dict[str, object]) -> None:
    with contextlib.suppress(OSError):
        sock.send(json.dumps(message).encode())


def _start_child(sock: socket.socket, request: Request, launcher_pid: int) -> Request | _Starting:
    """Start the component as the launcher's child: made so directly where the kernel allows it (clone with
    CLONE_PARENT, `_clone_for_launcher`), else through an intermediate that forks the component and exits at
    once, re-parenting it to the launcher before its pid is reported, so the launcher's waitpid() never races
    the re-parenting.

    The component reports its pid itself once it leads a session of its own, so that the launcher's first
    signal to its group finds the group. It starts with the stop signals blocked (`become` unblocks them
    once its handlers are in place): one sent meanwhile waits for it instead of meeting the zygote's
    SIG_IGN (a Ctrl-C right at the start was lost, and the component ran on)."""
    r, w = os.pipe()
    held = signal.pthread_sigmask(signal.SIG_BLOCK, STOP_SIGNALS)
    middle = None
    try:
        component = _clone_for_launcher() if os.getppid() == launcher_pid else None
        if component is None:
            middle = os.fork()
    except OSError as e:
        signal.pthread_sigmask(signal.SIG_SETMASK, held)
        os.close(r)
        os.close(w)
        return _Starting(answer={"error": f"fork failed: {e.strerror}"})
    if component == 0:
        os.close(r)
        _start_component(sock, launcher_pid, w)
        return request
    if middle == 0:
        os.close(r)
        try:
            pid = os.fork()
        except OSError:
            os._exit(1)
        if pid == 0:
            _start_component(sock, launcher_pid, w)
            return request
        os._exit(0)
    signal.pthread_sigmask(signal.SIG_SETMASK, held)
    os.close(w)
    return _Starting(report=r, middle=middle)


def _start_component(sock: socket.socket, launcher_pid: int, report_fd: int) -> None:
    try:
        sock.close()
        _settle(launcher_pid, report_fd)
    except BaseException:
        os._exit(1)  # never back into the server's code


# clone(2) as glibc's fork() makes it on x86_64 Linux (the kernel writes the child's thread id into the calling
# thread's glibc descriptor, and clears it at exit), plus CLONE_PARENT: the child is the launcher's, not the
# server's, so no intermediate has to fork it again and exit (a second fork of a 110 MB process, its exit and
# its reaping: 10-40 ms a component under load, five of them in a row before the second spawner).
SYS_CLONE_X86_64 = 56
SYS_GETTID_X86_64 = 186
CLONE_FLAGS = 0x00008000 | 0x01000000 | 0x00200000  # CLONE_PARENT | CLONE_CHILD_SETTID | CLONE_CHILD_CLEARTID
# where glibc keeps a thread's id in its descriptor (struct pthread's `tid`, x86_64, glibc 2.17-2.40); it is
# checked against gettid() before use, and the server forks twice when it does not hold
GLIBC_TID_OFFSET = 720
_clone_call: tuple[ctypes.PyDLL, int] | bool | None = False  # False: not looked at yet


def _clone_for_launcher() -> int | None:
    """As os.fork() (0 in the child, its pid in the server), the child being the launcher's; None where that
    is not possible here (then nothing was started)."""
    global _clone_call
    if _clone_call is False:
        _clone_call = _clone_support()
    if _clone_call is None or not _single_threaded():
        return None  # with other threads, glibc's fork() takes its locks around the fork: left to it
    libc, tid_address = _clone_call
    api = ctypes.pythonapi  # the interpreter's own steps around fork(): locks, threads, at-fork hooks
    api.PyOS_BeforeFork()
    pid = libc.syscall(ctypes.c_long(SYS_CLONE_X86_64), ctypes.c_ulong(CLONE_FLAGS | signal.SIGCHLD),
                       ctypes.c_void_p(0), ctypes.c_void_p(0), ctypes.c_void_p(tid_address), ctypes.c_ulong(0))
    if pid == 0:
        api.PyOS_AfterFork_Child()
        return 0
    errno = ctypes.get_errno()
    api.PyOS_AfterFork_Parent()
    if pid < 0:
        if errno in (1, 22):  # EPERM, EINVAL: the kernel or a sandbox refuses CLONE_PARENT here
            _clone_call = None
            return None
        raise OSError(errno, os.strerror(errno))
    return pid


def _single_threaded() -> bool:
    try:
        return len(os.listdir("/proc/self/task")) == 1
    except OSError:
        return False


def _clone_support() -> tuple[ctypes.PyDLL, int] | None:
    if os.environ.get("DIFFCTL_FORK_CLONE", "1") == "0" or not sys.platform.startswith("linux"):
        return None
    if os.uname().machine != "x86_64":
        return None  # clone's argument order and the descriptor's layout differ elsewhere
    try:
        libc = ctypes.PyDLL(None, use_errno=True)  # PyDLL: the GIL stays held across the call, as around fork()
        libc.syscall.restype = ctypes.c_long
        libc.pthread_self.restype = ctypes.c_void_p
        libc.gnu_get_libc_version.restype = ctypes.c_char_p
        libc.gnu_get_libc_version()  # glibc, not another C library
        tid_address = libc.pthread_self() + GLIBC_TID_OFFSET
        if ctypes.c_int.from_address(tid_address).value != libc.syscall(ctypes.c_long(SYS_GETTID_X86_64)):
            return None
    except (AttributeError, OSError, ValueError):
        return None
    return libc, tid_address


def _settle(launcher_pid: int, report_fd: int) -> None:
    """In the component: its own session, its pid reported, then the launcher as parent before the death
    signal is armed (a death signal armed earlier would fire when the intermediate exits)."""
    os.setsid()
    os.write(report_fd, str(os.getpid()).encode())
    os.close(report_fd)
    middle = os.getppid()
    deadline = time.monotonic() + 10.0
    while True:
        parent = os.getppid()  # read once: the intermediate may exit between two reads
        if parent == launcher_pid:
            break
        if parent != middle or time.monotonic() > deadline:
            os._exit(1)  # re-parented elsewhere: the launcher is gone
        time.sleep(0.0002)
    if sys.platform.startswith("linux"):
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
        if os.getppid() != launcher_pid:
            os._exit(1)  # the launcher died before the death signal was armed


def become(request: Request, start_cwd: str) -> None:
    """Turn this forked process into `python -m diffctl ARGS…` with the request's pipes, env and cwd."""
    devnull = os.open(os.devnull, os.O_RDONLY)
    os.dup2(devnull, 0)
    os.dup2(request.stdout_fd, 1)
    os.dup2(request.stderr_fd, 2)
    os.closerange(3, _max_fd())
    for sig in (signal.SIGTERM, signal.SIGHUP, signal.SIGUSR1, signal.SIGCHLD):
        signal.signal(sig, signal.SIG_DFL)
    signal.signal(signal.SIGINT, signal.default_int_handler)
    interrupted = signal.SIGINT in signal.sigpending()
    os.environ.clear()
    os.environ.update(request.env)
    if request.cwd:
        os.chdir(request.cwd)
    if sys.path and sys.path[0] == start_cwd:
        sys.path[0] = os.getcwd()  # `python -m` puts the working directory first on the path
    sys.argv = [request.argv[0], *request.argv[3:]]
    with contextlib.suppress(AttributeError):
        sys.orig_argv = list(request.argv)  # type: ignore[misc]
    retitle(request.argv)
    if "numpy.random" in sys.modules:
        sys.modules["numpy.random"].seed()  # numpy's global generator was seeded once, in the zygote
    if interrupted:
        sys.exit(130)  # a Ctrl-C came before diffctl's main could hear it: it ends as main does on one
    try:
        # a SIGTERM that came since the fork ends the process now, as it would have ended an exec'd one; a
        # SIGINT raises KeyboardInterrupt, before diffctl's main or inside it
        signal.pthread_sigmask(signal.SIG_UNBLOCK, STOP_SIGNALS)
        runpy.run_module("diffctl", run_name="__main__", alter_sys=True)
    except KeyboardInterrupt:
        sys.exit(130)


def retitle(argv: list[str]) -> None:
    """Write `argv` over this process's own argv memory, for /proc/PID/cmdline.

    The words are joined by spaces and end in a NUL, and the last byte of the area is not a NUL: the kernel
    then reads the command line up to that first NUL (its setproctitle rule), and ps and psutil split it
    at the spaces. The environment block that follows argv is left alone."""
    try:
        with open("/proc/self/stat") as stat:
            fields = stat.read().rsplit(")", 1)[1].split()
        start, end = int(fields[45]), int(fields[46])  # arg_start, arg_end (fields 48 and 49 of proc(5))
    except (OSError, IndexError, ValueError):
        return
    size = end - start
    if size < 2:
        return
    text = " ".join(argv).encode()[: size - 2]
    area = text + b"\0" * (size - len(text) - 1) + b" "
    ctypes.memmove(start, area, size)


def _max_fd() -> int:
    try:
        return int(os.sysconf("SC_OPEN_MAX"))
    except (ValueError, OSError):
        return 65536


def main() -> None:
    fd = int(sys.argv[1])
    spec = Preload.from_json(sys.argv[2] if len(sys.argv) > 3 else "")
    launcher_pid = os.getppid()
    start_cwd = os.getcwd()
    sock = socket.socket(fileno=fd)
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # only the launcher's close or its death ends the server
    preload(spec)
    global _clone_call
    _clone_call = _clone_support()  # looked at now, not at the first request
    request = serve(sock, launcher_pid, spec.later)
    if request is None:
        os._exit(0)  # the launcher is done: nothing of this process needs finalising
    become(request, start_cwd)


if __name__ == "__main__":
    main()
