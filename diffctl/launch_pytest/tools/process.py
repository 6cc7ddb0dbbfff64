"""Waiting, from a launch_pytest test, for a process of the launch to start, print, or exit: each wait
registers an event handler on the launch context for as long as it waits (async versions for async tests,
`_sync` versions for plain tests, which run on a thread while the launch's loop runs).

A start or exit that already happened counts: a test that begins after its process started or ended does not
wait for an event that will never come again.
"""

from __future__ import annotations

import asyncio
import contextlib
import threading
import time
from collections.abc import Callable, Iterator
from typing import Any

from diffctl.launch.event_handlers import OnProcessExit, OnProcessIO, OnProcessStart


@contextlib.contextmanager
def register_event_handler(context: Any, event_handler: Any) -> Iterator[Any]:
    """`event_handler` registered on `context` inside the with block."""
    try:
        yield context.register_event_handler(event_handler, append=True)
    finally:
        context.unregister_event_handler(event_handler)


def _started(action: Any) -> bool:
    return action.process_details is not None


def _exited(action: Any) -> bool:
    return action.return_code is not None


def _on_start(action: Any, event: Any) -> Any:
    return OnProcessStart(target_action=action, on_start=lambda e, c: event.set())


def _on_exit(action: Any, event: Any) -> Any:
    return OnProcessExit(target_action=action, on_exit=lambda e, c: event.set())


def _on_stdout(action: Any, event: Any) -> Any:
    return OnProcessIO(target_action=action, on_stdout=lambda e: event.set())


def _on_stderr(action: Any, event: Any) -> Any:
    return OnProcessIO(target_action=action, on_stderr=lambda e: event.set())


def _left(deadline: float | None) -> float | None:
    return None if deadline is None else max(0.0, deadline - time.monotonic())


async def _wait_until(context: Any, action: Any, handler_for: Callable[[Any, Any], Any],
                      condition: Callable[[], Any], timeout: float | None) -> Any:
    """Re-check `condition` at every event the handler sees, until it holds or `timeout` runs out."""
    event = asyncio.Event()
    deadline = None if timeout is None else time.monotonic() + timeout
    with register_event_handler(context, handler_for(action, event)):
        value = condition()
        while not value:
            left = _left(deadline)
            if left == 0.0:
                break
            try:
                await asyncio.wait_for(event.wait(), left)
            except TimeoutError:
                break
            event.clear()
            value = condition()
    return value


def _wait_until_sync(context: Any, action: Any, handler_for: Callable[[Any, Any], Any],
                     condition: Callable[[], Any], timeout: float | None) -> Any:
    event = threading.Event()
    deadline = None if timeout is None else time.monotonic() + timeout
    with register_event_handler(context, handler_for(action, event)):
        value = condition()
        while not value:
            left = _left(deadline)
            if left == 0.0 or not event.wait(left):
                break
            event.clear()
            value = condition()
    return value


def _asserting(validate: Callable[[str], Any], read: Callable[[], str]) -> Callable[[], bool]:
    def holds() -> bool:
        try:
            validate(read())
        except AssertionError:
            return False
        return True

    return holds


async def wait_for_start(launch_context: Any, execute_process_action: Any, timeout: float | None = None) -> bool:
    """Whether the process has started (waiting up to `timeout` s for it)."""
    return bool(await _wait_until(launch_context, execute_process_action, _on_start,
                                  lambda: _started(execute_process_action), timeout))


def wait_for_start_sync(launch_context: Any, execute_process_action: Any, timeout: float | None = None) -> bool:
    return bool(_wait_until_sync(launch_context, execute_process_action, _on_start,
                                 lambda: _started(execute_process_action), timeout))


async def wait_for_exit(launch_context: Any, execute_process_action: Any, timeout: float | None = None) -> bool:
    """Whether the process has exited (waiting up to `timeout` s for it)."""
    return bool(await _wait_until(launch_context, execute_process_action, _on_exit,
                                  lambda: _exited(execute_process_action), timeout))


def wait_for_exit_sync(launch_context: Any, execute_process_action: Any, timeout: float | None = None) -> bool:
    return bool(_wait_until_sync(launch_context, execute_process_action, _on_exit,
                                 lambda: _exited(execute_process_action), timeout))


async def wait_for_output(launch_context: Any, execute_process_action: Any, validate_output: Callable[[str], Any],
                          timeout: float | None = None) -> Any:
    """Wait until `validate_output(stdout so far)` is true (the action needs cached_output=True); its last
    answer."""
    return await _wait_until(launch_context, execute_process_action, _on_stdout,
                             lambda: validate_output(execute_process_action.get_stdout()), timeout)


def wait_for_output_sync(launch_context: Any, execute_process_action: Any, validate_output: Callable[[str], Any],
                         timeout: float | None = None) -> Any:
    return _wait_until_sync(launch_context, execute_process_action, _on_stdout,
                            lambda: validate_output(execute_process_action.get_stdout()), timeout)


async def assert_output(launch_context: Any, execute_process_action: Any, validate_output: Callable[[str], Any],
                        timeout: float | None = None) -> None:
    """Wait until `validate_output(stdout so far)` raises no AssertionError; at the timeout, its error."""
    holds = _asserting(validate_output, execute_process_action.get_stdout)
    if not await _wait_until(launch_context, execute_process_action, _on_stdout, holds, timeout):
        validate_output(execute_process_action.get_stdout())


def assert_output_sync(launch_context: Any, execute_process_action: Any, validate_output: Callable[[str], Any],
                       timeout: float | None = None) -> None:
    holds = _asserting(validate_output, execute_process_action.get_stdout)
    if not _wait_until_sync(launch_context, execute_process_action, _on_stdout, holds, timeout):
        validate_output(execute_process_action.get_stdout())


async def wait_for_stderr(launch_context: Any, execute_process_action: Any, validate_output: Callable[[str], Any],
                          timeout: float | None = None) -> Any:
    """wait_for_output on stderr."""
    return await _wait_until(launch_context, execute_process_action, _on_stderr,
                             lambda: validate_output(execute_process_action.get_stderr()), timeout)


def wait_for_stderr_sync(launch_context: Any, execute_process_action: Any, validate_output: Callable[[str], Any],
                         timeout: float | None = None) -> Any:
    return _wait_until_sync(launch_context, execute_process_action, _on_stderr,
                            lambda: validate_output(execute_process_action.get_stderr()), timeout)


async def assert_stderr(launch_context: Any, execute_process_action: Any, validate_output: Callable[[str], Any],
                        timeout: float | None = None) -> None:
    """assert_output on stderr."""
    holds = _asserting(validate_output, execute_process_action.get_stderr)
    if not await _wait_until(launch_context, execute_process_action, _on_stderr, holds, timeout):
        validate_output(execute_process_action.get_stderr())


def assert_stderr_sync(launch_context: Any, execute_process_action: Any, validate_output: Callable[[str], Any],
                       timeout: float | None = None) -> None:
    holds = _asserting(validate_output, execute_process_action.get_stderr)
    if not _wait_until_sync(launch_context, execute_process_action, _on_stderr, holds, timeout):
        validate_output(execute_process_action.get_stderr())
