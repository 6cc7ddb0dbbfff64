"""Trying several ways in turn (the frontends on a file, Python or markup on a launch file)."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import TypeVar

T = TypeVar('T')


class NoneWorked(Exception):
    """Every attempt raised; `failures` holds what each raised, in order."""

    def __init__(self, failures: list[Exception]) -> None:
        super().__init__(f'{len(failures)} attempts failed')
        self.failures = failures


def first_success(attempts: Iterable[Callable[[], T]], *, after_failure: Callable[[], object] | None = None) -> T:
    """The result of the first attempt that raises nothing; `after_failure` runs after each one that does."""
    failures: list[Exception] = []
    for attempt in attempts:
        try:
            return attempt()
        except Exception as failure:
            failures.append(failure)
        if after_failure is not None:
            after_failure()
    raise NoneWorked(failures)
