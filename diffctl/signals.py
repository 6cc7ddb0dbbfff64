"""Ending a command-line tool's loop on Ctrl-C or SIGTERM (echo, pub, hz, bag record and play)."""

from __future__ import annotations

import signal
import threading


def stop_on_signals() -> threading.Event:
    """An event that SIGINT or SIGTERM sets: the tool finishes its loop, closes what it wrote, and exits 0."""
    stop = threading.Event()
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: stop.set())
    return stop
