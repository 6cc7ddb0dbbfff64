"""Turning SIGINT, SIGTERM and SIGHUP into a stop event, so teleop loops end by sending their zero command."""

from __future__ import annotations

import signal
import threading


def stop_on_signals(stop: threading.Event) -> None:
    # Signal handlers can only be installed from the main thread; loops run elsewhere (tests) rely on `stop`.
    if threading.current_thread() is threading.main_thread():
        for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            signal.signal(sig, lambda *_: stop.set())
