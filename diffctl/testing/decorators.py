"""launch_testing's decorators and the ReadyToTest action: how a test file marks what it wants.

`@launch_testing.parametrize('a, b', [(1, 2), …])` makes one run per value, `@launch_testing.markers.keep_alive`
keeps the launch up when every process has exited, `@launch_testing.ready_to_test_action_timeout(s)` bounds the
wait for ReadyToTest, `@launch_testing.post_shutdown_test()` puts a TestCase after the launch ended.
"""

from __future__ import annotations

import functools
import inspect
import time
from collections.abc import Callable, Iterable, Iterator
from typing import Any

from diffctl.launch_legacy.actions import Action


class ReadyToTest(Action):
    """Visited when the processes under test have been started: the launch test's tests begin then."""

    def __init__(self, **kw: Any) -> None:
        super().__init__(**kw)
        self._callbacks: list[Callable[[], None]] = []

    def _add_callback(self, callback: Callable[[], None]) -> None:
        self._callbacks.append(callback)

    def label(self) -> str:
        return "ReadyToTest"

    def execute(self, context: Any) -> None:
        for callback in self._callbacks:
            callback()
        return None


def _markers(fn: Any) -> dict[str, Any]:
    if not hasattr(fn, "__markers__"):
        fn.__markers__ = {}
    return fn.__markers__


def keep_alive(fn: Callable[..., Any]) -> Callable[..., Any]:
    """The launch is not shut down when nothing is left running (tests start processes themselves)."""
    _markers(fn)["keep_alive"] = True
    return fn


def retry_on_failure(*, times: int, delay: float | None = None) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """A test method that is run again (up to `times` times in all) while it fails."""
    if times < 1:
        raise ValueError("times must be >= 1")

    def decorator(method: Callable[..., Any]) -> Callable[..., Any]:
        @functools.wraps(method)
        def wrapper(*args: Any, **kwargs: Any) -> Any:
            for attempt in range(times):
                try:
                    return method(*args, **kwargs)
                except AssertionError:
                    if attempt == times - 1:
                        raise
                    if delay:
                        time.sleep(delay)
            return None

        return wrapper

    return decorator


def ready_to_test_action_timeout(timeout_s: float) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    def decorator(fn: Callable[..., Any]) -> Callable[..., Any]:
        fn.__ready_to_test_action_timeout__ = timeout_s
        return fn

    return decorator


def post_shutdown_test() -> Callable[[type], type]:
    """The TestCase runs after the launch has shut down (exit codes, whole output)."""

    def decorator(cls: type) -> type:
        if not inspect.isclass(cls):
            raise TypeError("post_shutdown_test() decorates TestCase classes only")
        cls.__post_shutdown_test__ = True
        return cls

    return decorator


def parametrize(argnames: str, argvalues: Iterable[Any]) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """One launch (and one run of every test) per value; the values are named arguments of
    generate_test_description and of the tests that ask for them."""
    names = [n.strip() for n in argnames.split(",") if n.strip()]
    values = list(argvalues)

    def decorator(fn: Callable[..., Any]) -> Callable[..., Any]:
        parameters = list(inspect.signature(fn).parameters)
        for name in names:
            if name not in parameters:
                raise Exception(f"Could not find an argument in generate_test_description matching "
                                f"prametrized argument '{name}'")
        for name in parameters:
            if name not in names:
                raise Exception(f"generate_test_description has unexpected extra argument '{name}'")

        @functools.wraps(fn)
        def runs() -> Iterator[tuple[Callable[..., Any], dict[str, Any]]]:
            for value in values:
                row = value if isinstance(value, tuple) else (value,)
                if len(row) != len(names):
                    raise Exception(f"parametrize: {value!r} does not give one value for each of {names}")
                args = dict(zip(names, row, strict=True))
                yield functools.partial(fn, **args), args

        runs.__parametrized__ = True  # type: ignore[attr-defined]
        runs.__markers__ = _markers(fn)  # type: ignore[attr-defined]
        return runs

    return decorator
