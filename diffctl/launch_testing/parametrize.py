"""`@launch_testing.parametrize('a, b', [(1, 2), …])`: one launch, and one run of the tests, per value."""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterable, Iterator
from typing import Any


def _as_row(value: Any) -> tuple[Any, ...]:
    return value if isinstance(value, tuple) else (value,)


def parametrize(argnames: str, argvalues: Iterable[Any]) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """As pytest.mark.parametrize, on generate_test_description: `argnames` is a comma-separated list, each
    of `argvalues` a tuple of that many values (or one bare value). The decorated function yields, per value,
    generate_test_description with those arguments bound (others it takes may still be given at the call)
    and the dict of them; the tests of each run can take them by name."""
    names = [name.strip() for name in argnames.split(",") if name.strip()]
    rows = [_as_row(value) for value in argvalues]

    def decorator(func: Callable[..., Any]) -> Callable[..., Any]:
        @functools.wraps(func)
        def runs() -> Iterator[tuple[Callable[..., Any], dict[str, Any]]]:
            for row in rows:
                bound = dict(zip(names, row, strict=False))  # a short row binds what it has
                yield functools.update_wrapper(functools.partial(func, **bound), func), bound

        runs.__parametrized__ = True  # type: ignore[attr-defined]
        timeout = getattr(func, "__ready_to_test_action_timeout__", None)
        if timeout is not None:
            runs.__ready_to_test_action_timeout__ = timeout  # type: ignore[attr-defined]
        return runs

    return decorator
