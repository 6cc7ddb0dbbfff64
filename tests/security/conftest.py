"""Fixtures of the security tests: two network-namespace hosts, and programs whose output a test waits on."""

from __future__ import annotations

import re
import subprocess
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass, field

import pytest

from tests.security.netns import HostPair, netns_unavailable


@dataclass
class Running:
    """A started program and everything it has printed so far (read by a thread, so it never blocks)."""

    proc: subprocess.Popen
    lines: list[str] = field(default_factory=list)

    def __post_init__(self) -> None:
        threading.Thread(target=self._pump, daemon=True).start()

    def _pump(self) -> None:
        for line in self.proc.stdout:  # type: ignore[union-attr]
            self.lines.append(line)

    def output(self) -> str:
        return "".join(self.lines)

    def wait_for(self, pattern: str, timeout_s: float = 30.0) -> re.Match[str]:
        rx = re.compile(pattern)
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            for line in list(self.lines):
                if m := rx.search(line):
                    return m
            if self.proc.poll() is not None:
                time.sleep(0.2)  # the last lines
                raise AssertionError(f"exited {self.proc.returncode} before {pattern!r}:\n{self.output()}")
            time.sleep(0.05)
        raise AssertionError(f"no {pattern!r} within {timeout_s} s:\n{self.output()}")


@pytest.fixture
def hosts() -> Iterator[HostPair]:
    """Host A and host B, network namespaces on a veth pair; skipped, saying why, where they cannot be made."""
    reason = netns_unavailable()
    if reason:
        pytest.skip(reason=reason)
    pair = HostPair.create()
    try:
        yield pair
    finally:
        pair.remove()
        assert not pair.exists(), "a test namespace survived its test"
