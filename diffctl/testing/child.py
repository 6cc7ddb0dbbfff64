"""`python -m diffctl.testing.child MODULE ARGS…`: run MODULE as `python -m` would, dying with `diffctl test`.

Each test file runs in a session of its own (so a timeout can kill all of it); with the death signal armed
here, a `diffctl test` that is itself killed (a cancelled CI job) takes its tests, and through their own death
signals and guards every process they started, along.
"""

from __future__ import annotations

import ctypes
import os
import runpy
import signal
import sys

PR_SET_PDEATHSIG = 1
PARENT_ENV = "DIFFCTL_TEST_PARENT_PID"


def arm_death_signal() -> None:
    parent = os.environ.pop(PARENT_ENV, "")
    if not parent or not sys.platform.startswith("linux"):
        return
    try:
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    except (OSError, AttributeError):
        return
    if os.getppid() != int(parent):
        os._exit(1)  # diffctl test died before the signal was armed


def main() -> None:
    arm_death_signal()
    if len(sys.argv) < 2:
        sys.exit("usage: python -m diffctl.testing.child MODULE [ARG ...]")
    module = sys.argv[1]
    sys.argv = sys.argv[1:]
    runpy.run_module(module, run_name="__main__", alter_sys=True)


if __name__ == "__main__":
    main()
