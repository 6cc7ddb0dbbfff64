"""Markers of launch tests: keep a launch up when its processes end, retry a flaky test method."""

from __future__ import annotations

import functools
import inspect
import time
import unittest
from collections.abc import Callable
from typing import Any


def keep_alive(test_description: Callable[..., Any]) -> Callable[..., Any]:
    """On generate_test_description: the launch is not shut down when every process has exited (the tests
    end it)."""
    markers = getattr(test_description, "__markers__", None)
    if markers is None:
        markers = test_description.__markers__ = {}  # type: ignore[attr-defined]
    markers["keep_alive"] = True
    return test_description


def _forget_failures(case: Any) -> None:
    """unittest records an AssertionError of a subTest in the case's outcome: a retried attempt starts clean."""
    outcome = getattr(case, "_outcome", None)
    if outcome is None:
        return
    if hasattr(outcome, "errors"):
        outcome.errors.clear()
    elif getattr(outcome, "result", None) is not None:
        outcome.result.errors.clear()
    outcome.success = True


def retry_on_failure(*, times: int, delay: float | None = None) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """On a test method: run it up to `times` times while it fails with an AssertionError, `delay` seconds
    apart; the last attempt's failure is the test's."""
    assert times > 0

    def decorator(method: Callable[..., Any]) -> Callable[..., Any]:
        assert next(iter(inspect.signature(method).parameters)) == "self"

        @functools.wraps(method)
        def attempt(self: Any, *args: Any, **kwargs: Any) -> Any:
            for _ in range(times - 1):
                try:
                    value = method(self, *args, **kwargs)
                    if isinstance(self, unittest.TestCase) and not self._outcome.success:
                        raise AssertionError  # a failed subTest counts as a failure of this attempt
                    return value
                except AssertionError:
                    _forget_failures(self)
                if delay is not None:
                    time.sleep(delay)
            return method(self, *args, **kwargs)

        return attempt

    return decorator
