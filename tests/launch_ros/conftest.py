"""launch_ros's tests: launches run to their end in this process; whatever a failing one left running is
killed here (and fails the test)."""

from __future__ import annotations

import logging
from collections.abc import Iterator
from pathlib import Path

import psutil
import pytest

DATA = Path(__file__).resolve().parent / "data"


@pytest.fixture(autouse=True)
def no_children_left() -> Iterator[None]:
    """Autouse, so torn down after the test's other fixtures (the router's process included). Only what this
    test started counts (an earlier test's zombie is its own business)."""
    me = psutil.Process()
    before = {p.pid for p in me.children(recursive=True)}
    yield
    left = [p for p in me.children(recursive=True) if p.pid not in before]
    for child in left:
        try:
            child.kill()
        except psutil.NoSuchProcess:
            pass
    psutil.wait_procs(left, timeout=5)
    assert not left, f"processes left running: {[p.pid for p in left]}"


class Records(logging.Handler):
    """The messages of one logger, whatever handlers launch.logging gave it."""

    def __init__(self, name: str) -> None:
        super().__init__()
        self.messages: list[str] = []
        self.logger = logging.getLogger(name)

    def emit(self, record: logging.LogRecord) -> None:
        self.messages.append(record.getMessage())

    def __enter__(self) -> Records:
        self.logger.addHandler(self)
        return self

    def __exit__(self, *exc: object) -> None:
        self.logger.removeHandler(self)


def run(entities: list, **service_kwargs) -> tuple[int, object]:
    """Run a launch of `entities` to its end: (return code, its LaunchContext)."""
    from diffctl.launch import LaunchDescription, LaunchService

    service = LaunchService(**service_kwargs)
    service.include_launch_description(LaunchDescription(entities))
    return service.run(), service.context
