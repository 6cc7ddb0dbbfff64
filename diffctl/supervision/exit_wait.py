"""Waiting for a child process's exit without polling: its pidfd wakes the wait (the fork server, the guard).

No asyncio here: the fork server is started, and may be ended, before the launcher imports it.
"""

from __future__ import annotations

import os
import select
import subprocess


def wait_exited(process: subprocess.Popen, timeout_s: float) -> bool:
    """Reap `process` (a Popen, or anything with its `pid` and `wait()`) once it exits, waiting at most
    `timeout_s`; False if it still runs then.

    Woken by the process's pidfd as it exits: `Popen.wait(timeout)` polls, sleeping up to 50 ms at a time."""
    if getattr(process, 'returncode', None) is not None:
        return True  # reaped: its pid may be another process's by now
    try:
        pidfd = os.pidfd_open(process.pid)
    except ProcessLookupError:  # reaped already
        process.wait()
        return True
    except (AttributeError, OSError):  # no pidfd here
        try:
            process.wait(timeout_s)
        except subprocess.TimeoutExpired:
            return False
        return True
    try:
        exited, _, _ = select.select([pidfd], [], [], timeout_s)
    finally:
        os.close(pidfd)
    if exited:
        process.wait()
    return bool(exited)
