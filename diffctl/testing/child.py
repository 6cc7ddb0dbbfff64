"""`python -m diffctl.testing.child launch_test|pytest|pytest-isolated ARGS…`: one test file's run, dying with
`diffctl test`.

Each test file runs in a session of its own (so a timeout can kill all of it); with the death signal armed
here, a `diffctl test` that is itself killed (a cancelled CI job) takes its tests, and through their own death
signals and guards every process they started, along. The runners are called as functions, not run as
`__main__` modules: a module already imported (the shared zygote preloads them) is not executed twice.
"""

from __future__ import annotations

import atexit
import contextlib
import ctypes
import os
import select
import signal
import sys
import threading
import time

PR_SET_PDEATHSIG = 1
PARENT_ENV = "DIFFCTL_TEST_PARENT_PID"
ISOLATED_ENV = "DIFFCTL_TEST_ISOLATED"  # the session is on a bus of its own already (pytest_isolation.py)


def die_with_parent(runner: str) -> None:
    """The signal this process gets when its parent dies. A launch_test run is killed outright: its launch's
    spawner (diffctl launch's) kills everything the launch started once it is gone (death signals, the
    guard). A pytest run is interrupted: a launch_pytest launch (launch's own spawner) then shuts its
    processes down as on Ctrl-C."""
    if not sys.platform.startswith("linux"):
        return
    sig = signal.SIGKILL if runner == "launch_test" else signal.SIGINT  # pytest: watch_parent finishes it
    try:
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, sig, 0, 0, 0)
    except (OSError, AttributeError):
        pass


def watch_parent(grace_s: float = 3.0) -> None:
    """For a pytest run: when the parent is gone, interrupt this process (a launch on its loop shuts down), and
    end it `grace_s` later whatever it is doing (a test body blocked in its thread would keep it alive), with
    its exit handlers run first (supervision's kills every process group a launch still has)."""
    try:
        parent = os.pidfd_open(os.getppid())
    except (AttributeError, OSError):
        return

    def watch() -> None:
        select.select([parent], [], [])
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(grace_s)
        with contextlib.suppress(Exception):
            atexit._run_exitfuncs()
        os._exit(1)

    threading.Thread(target=watch, name="watch_parent", daemon=True).start()


def arm_death_signal(runner: str) -> None:
    parent = os.environ.pop(PARENT_ENV, "")
    if not parent or not sys.platform.startswith("linux"):
        return
    die_with_parent(runner)
    if os.getppid() != int(parent):
        os._exit(1)  # diffctl test died before the signal was armed


def _pytest(args: list[str], isolated: bool) -> int:
    """pytest on one file; `isolated` (launch_pytest files): on a bus of its own, which its launches and its
    test bodies share. Plain pytest files need no router."""
    import pytest

    watch_parent()
    if not isolated:
        os.environ[ISOLATED_ENV] = "1"  # nothing to isolate: pytest_isolation.py starts no router
        return int(pytest.main(args))
    from diffctl.testing.isolation import isolated_bus

    with isolated_bus():
        os.environ[ISOLATED_ENV] = "1"
        return int(pytest.main(args))


def run(runner: str, args: list[str]) -> int:
    if runner == "launch_test":
        from diffctl.testing.launch_test import run as launch_test

        return launch_test(args)
    if runner in ("pytest", "pytest-isolated"):
        return _pytest(args, isolated=runner == "pytest-isolated")
    print(f"diffctl.testing.child: unknown runner {runner!r} (launch_test, pytest or pytest-isolated)",
          file=sys.stderr)
    return 2


def main() -> None:
    if len(sys.argv) < 2:
        sys.exit("usage: python -m diffctl.testing.child launch_test|pytest|pytest-isolated [ARG ...]")
    arm_death_signal(sys.argv[1])
    code = run(sys.argv[1], sys.argv[2:])
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)  # the teardown of zenoh's and rclpy's threads would only add time


if __name__ == "__main__":
    main()
