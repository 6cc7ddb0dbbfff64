"""The guard: a tiny process that kills the launcher's process groups if the launcher dies.

Children get PR_SET_PDEATHSIG, but that reaches only direct children: the grandchild of a `shell: true`
process would outlive a SIGKILLed launcher. The launcher writes `+PGID` / `-PGID` lines to the guard's
stdin as groups come and go, and `exit` when it ends normally; end-of-file without `exit` means the
launcher died, and the guard SIGKILLs every group it knows. Standard library only: it runs as
`python -I -S guard.py` so it starts in milliseconds.
"""

import os
import signal


def main() -> None:
    # Terminal signals are for the launcher; the guard ends only with its input.
    for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT, signal.SIGTSTP):
        signal.signal(sig, signal.SIG_IGN)
    groups: set[int] = set()
    pending = b""
    while True:
        try:
            data = os.read(0, 4096)
        except InterruptedError:
            continue
        if not data:
            break
        pending += data
        *lines, pending = pending.split(b"\n")
        for line in lines:
            if line == b"exit":
                return
            if line[:1] == b"+":
                groups.add(int(line[1:]))
            elif line[:1] == b"-":
                groups.discard(int(line[1:]))
    for pgid in groups:
        try:
            os.killpg(pgid, signal.SIGKILL)
        except OSError:
            pass


if __name__ == "__main__":
    main()
