"""The asyncio loop launch runs on: the thread's current loop, made when there is none."""

from __future__ import annotations

import asyncio
import warnings


def get_loop() -> asyncio.AbstractEventLoop:
    """The running loop, else this thread's event loop (created and set when missing or closed).

    It is the loop `asyncio.get_event_loop()` (and osrf_pycommon's `get_loop()`) returns, so code driving
    `LaunchService.run_async()` itself and code calling `run()` share it.
    """
    try:
        return asyncio.get_running_loop()
    except RuntimeError:
        pass
    with warnings.catch_warnings():
        warnings.simplefilter('ignore', DeprecationWarning)
        try:
            loop = asyncio.get_event_loop_policy().get_event_loop()
        except RuntimeError:
            loop = None
    if loop is None or loop.is_closed():
        loop = asyncio.new_event_loop()
        asyncio.set_event_loop(loop)
    return loop
