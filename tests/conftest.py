"""Shared fixtures: a real Zenoh router on a free loopback port, and leak-proof child processes."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from bench.ports import free_port, wait_port

__all__ = ["OUTPUT", "REPO", "Procs", "free_port", "wait_port"]

# pytest rewrites the asserts of every test module as it imports it: ~15 s of CPU for this suite, in each
# pytest-xdist worker. Where PYTHONDONTWRITEBYTECODE is set it would redo that on every run; the rewritten
# modules are kept in tests/**/__pycache__ (ignored by git) instead, as `make bytecode` keeps diffctl's own.
# This process only: the programs the tests start keep the environment's setting.
sys.dont_write_bytecode = False

REPO = Path(__file__).resolve().parent.parent
OUTPUT = REPO / "test-output"


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The slow end-to-end tests first (in their files' order): under pytest-xdist the run then ends on short
    tests, every worker busy to the end, not one finishing a 30 s test while the others wait."""
    items.sort(key=lambda item: item.get_closest_marker("slow") is None)


class Procs:
    """Children started in their own process groups and always killed (group-wide) at teardown."""

    def __init__(self) -> None:
        self.procs: list[subprocess.Popen] = []

    def start(self, argv: list[str], **kw) -> subprocess.Popen:
        kw.setdefault("stdout", subprocess.PIPE)
        kw.setdefault("stderr", subprocess.STDOUT)
        kw.setdefault("text", True)
        p = subprocess.Popen(argv, start_new_session=True, **kw)
        self.procs.append(p)
        return p

    def diffctl(self, *args: str, **kw) -> subprocess.Popen:
        return self.start([sys.executable, "-m", "diffctl", *args], **kw)

    def stop(self, p: subprocess.Popen, sig: int = signal.SIGINT, timeout_s: float = 5.0) -> int:
        try:
            os.killpg(p.pid, sig)
        except ProcessLookupError:
            pass
        try:
            return p.wait(timeout_s)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            return p.wait()

    def close(self) -> None:
        for p in reversed(self.procs):
            try:
                os.killpg(p.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
            try:
                p.wait(5)
            except subprocess.TimeoutExpired:
                pass
            for stream in (p.stdout, p.stderr):
                if stream:
                    _show_rest(p, stream)
                    stream.close()


def _show_rest(p: subprocess.Popen, stream: Any) -> None:
    """Print what a child wrote that its test did not read (pytest shows it beside a failure): without it a
    failed wait says nothing of what the child was doing. Non-blocking: a grandchild in another session may
    still hold the pipe open."""
    try:
        os.set_blocking(stream.fileno(), False)
        rest = stream.read()
    except (OSError, ValueError, TypeError):  # TypeError: nothing to read yet (TextIOWrapper meets None)
        return
    if rest:
        text = rest if isinstance(rest, str) else rest.decode(errors="replace")
        print(f"--- output of {' '.join(map(str, p.args))[:200]} (exit {p.returncode}) not read by the test:")
        print(text[-8000:])


@pytest.fixture
def procs() -> Iterator[Procs]:
    ps = Procs()
    try:
        yield ps
    finally:
        ps.close()


@pytest.fixture
def router(monkeypatch: pytest.MonkeyPatch) -> Iterator[str]:
    """A real `diffctl router` on a free loopback port; DIFFCTL_ROUTER points this test and its children at it."""
    from diffctl.bus.session import close_session

    port = free_port()
    endpoint = f"tcp/127.0.0.1:{port}"
    monkeypatch.setenv("DIFFCTL_ROUTER", endpoint)
    ps = Procs()
    try:
        ps.diffctl("router", "--listen", endpoint, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        wait_port(port)
        yield endpoint
    finally:
        close_session()  # the in-test session belongs to this router
        ps.close()


@pytest.fixture
def output_dir(request: pytest.FixtureRequest) -> Path:
    """A per-test folder under test-output/ for screenshots and logs a person may want to look at."""
    d = OUTPUT / request.node.name.replace("/", "_").replace("[", "_").replace("]", "")
    d.mkdir(parents=True, exist_ok=True)
    return d
