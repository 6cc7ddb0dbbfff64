"""How a user's Python program, started from its sources, ends when the input it reads is bad.

A malformed workspace interface (`.msg`, `.srv`, `.action`) surfaces when the program imports it, as an
ImportError that is also one of diffctl's located errors. The generated console scripts catch exactly that
and end the program with the error's one line and exit code 2 instead of a traceback through the import
machinery. Under `diffctl run` the line goes to the command itself (a pipe whose descriptor the command
passes in REPORT_FD_ENV), which prints it as its own error, so the user sees it once and without ros2 run's
"Process exited with failure" after it.
"""

from __future__ import annotations

import os
import stat
import sys
from typing import NoReturn

REPORT_FD_ENV = "DIFFCTL_BAD_INPUT_FD"


def is_bad_input(error: BaseException) -> bool:
    """An import that failed on the user's own definitions (diffctl's located error), not a missing module."""
    from diffctl.errors import DiffctlError

    return isinstance(error, DiffctlError) and error.exit_code == 2


def exit_bad_input(error: BaseException, report_fd: str | None) -> NoReturn:
    """Say `error` in one line, to the command that started this program when it asked for it, and exit 2."""
    line = str(error)
    fd = int(report_fd) if report_fd and report_fd.isdigit() else -1
    try:
        if fd < 0 or not stat.S_ISFIFO(os.fstat(fd).st_mode):
            raise OSError
        os.write(fd, line.encode("utf-8", "replace"))
        os.close(fd)
    except OSError:
        from diffctl.console import error as say

        say(line)
    sys.stdout.flush()
    sys.exit(2)


__all__ = ["REPORT_FD_ENV", "exit_bad_input", "is_bad_input"]
