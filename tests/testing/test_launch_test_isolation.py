"""Launch tests run side by side on buses of their own; a hanging one is stopped with everything it started."""

from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import uuid
from pathlib import Path

import psutil
import pytest

FILES = Path(__file__).resolve().parent / "launch_tests"


@pytest.mark.slow
def test_two_tests_at_once_do_not_hear_each_other(tmp_path: Path) -> None:
    a, b = tmp_path / "a_crosstalk_launch_test.py", tmp_path / "b_crosstalk_launch_test.py"
    shutil.copy(FILES / "crosstalk_launch_test.py", a)
    shutil.copy(FILES / "crosstalk_launch_test.py", b)
    started = time.monotonic()
    r = subprocess.run([sys.executable, "-m", "diffctl", "test", str(a), str(b), "-j", "2"],
                       capture_output=True, text=True, timeout=120, start_new_session=True)
    took = time.monotonic() - started
    assert r.returncode == 0, r.stdout + r.stderr
    buses = set(re.findall(r"bus (tcp/127\.0\.0\.1:\d+) domain (\d+)", r.stdout))
    assert len(buses) == 2 and len({d for _, d in buses}) == 2, buses  # two routers, two domains
    each = [float(s) for s in re.findall(r"crosstalk_launch_test\.py: passed in ([0-9.]+) s", r.stdout)]
    assert len(each) == 2 and took < sum(each), (took, each)  # side by side, not one after the other


@pytest.mark.slow
def test_hanging_test_is_stopped_at_its_timeout_and_leaves_nothing(tmp_path: Path) -> None:
    marker = f"{4000 + uuid.uuid4().int % 1000}.{uuid.uuid4().int % 9 + 1}"
    env = {**os.environ, "HANG_MARKER": marker}
    started = time.monotonic()
    r = subprocess.run([sys.executable, "-m", "diffctl", "test", str(FILES / "hanging_launch_test.py"),
                        "--timeout", "4"], capture_output=True, text=True, timeout=60, env=env,
                       start_new_session=True)
    took = time.monotonic() - started
    assert r.returncode == 1
    assert "timed out after 4 s" in r.stdout and "hanging" in r.stdout
    assert took < 60  # stopped, not left to its 600 s sleep (a bound for a loaded machine)
    left = _left(marker)
    assert not left, [p.info["cmdline"] for p in left]


def _left(marker: str, within_s: float = 3.0) -> list[psutil.Process]:
    """The processes whose command line holds `marker`, once they are gone (or `within_s` has passed)."""
    deadline = time.monotonic() + within_s
    while True:
        left = [p for p in psutil.process_iter(["cmdline"]) if marker in " ".join(p.info["cmdline"] or [])]
        if not left or time.monotonic() > deadline:
            return left
        time.sleep(0.1)


@pytest.mark.slow
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGKILL], ids=["ctrl-c", "killed"])
def test_stopping_diffctl_test_stops_its_tests_and_their_processes(sig: int) -> None:
    """Ctrl-C (exit 130), or diffctl test killed outright (a cancelled CI job): nothing it started is left, from a
    launch_testing file (its launch on diffctl launch's spawner) nor from a launch_pytest one (its launch on launch's
    own, in a pytest session whose test body never returns)."""
    marker = f"{5000 + uuid.uuid4().int % 1000}.{uuid.uuid4().int % 9 + 1}"
    env = {**os.environ, "HANG_MARKER": marker}
    tmp = Path(tempfile.mkdtemp(prefix="diffctl-hang-"))
    shutil.copy(FILES / "pytest_hanging.py", tmp / "test_hanging_pytest.py")
    p = subprocess.Popen([sys.executable, "-m", "diffctl", "test", "-j", "2", str(FILES / "hanging_launch_test.py"),
                          str(tmp / "test_hanging_pytest.py")], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         text=True, env=env, start_new_session=True)
    try:
        deadline = time.monotonic() + 30
        while len(_left(marker)) < 6 and time.monotonic() < deadline:  # two shells, each with two sleeps
            time.sleep(0.1)
        assert len(_left(marker)) == 6, "the hanging tests never started"
        os.kill(p.pid, sig)
        # a failure bound only: a process deaf to SIGINT and SIGTERM is escalated 5 s + 5 s later (launch's
        # sigterm_timeout and sigkill_timeout), after the two runs' own teardown, which a loaded machine slows
        code = p.wait(60)
        assert code == (130 if sig == signal.SIGINT else -signal.SIGKILL)
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
        p.stdout.close()
        shutil.rmtree(tmp, ignore_errors=True)
    # Killed, diffctl test cannot wait for its pytest child: that one is interrupted and ends on its own, at the
    # latest its watch_parent grace (3 s) after; a loaded machine may need longer: the bound is generous.
    left = _left(marker, within_s=30.0)
    assert not left, [(q.pid, q.ppid(), q.info["cmdline"]) for q in left]


def _forked_tests() -> list[str]:
    return [" ".join(p.info["cmdline"] or []) for p in psutil.process_iter(["cmdline"])
            if "test-child" in (p.info["cmdline"] or [])]


@pytest.mark.slow
def test_tests_forked_from_the_shared_zygote_time_out_and_die_with_diffctl_test(tmp_path: Path) -> None:
    """With two launch tests, both are forked from one preloaded interpreter (`diffctl test-child`): a hanging
    one is still stopped at its timeout with everything it started, the other passes; a `diffctl test` killed
    outright takes its forked tests, their processes and the zygote along."""
    hang = tmp_path / "hang_launch_test.py"
    shutil.copy(FILES / "hanging_launch_test.py", hang)
    hello = tmp_path / "hello_world_launch_test.py"
    # The passing test lingers a second, so the 0.1 s sampling below sees its forked process on any machine (the
    # bare hello world can come and go between two samples).
    hello.write_text((FILES / "hello_world_launch_test.py").read_text()
                     + "\n\nclass TestLingers(unittest.TestCase):\n"
                     + "    def test_lingers(self):\n        __import__('time').sleep(1.5)\n")
    marker = f"{6000 + uuid.uuid4().int % 1000}.{uuid.uuid4().int % 9 + 1}"
    env = {**os.environ, "HANG_MARKER": marker}
    argv = [sys.executable, "-m", "diffctl", "test", "-j", "2", str(hang), str(hello)]
    p = subprocess.Popen([*argv, "--timeout", "20"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                         env=env, start_new_session=True)
    try:
        seen: set[str] = set()
        while p.poll() is None:
            seen.update(c for c in _forked_tests() if str(tmp_path) in c)
            time.sleep(0.1)
        out = p.stdout.read()
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
        p.stdout.close()
    assert p.returncode == 1, out
    assert any(str(hang) in c for c in seen) and any(str(hello) in c for c in seen), seen
    assert "hello_world_launch_test.py: passed" in out and "timed out after 20 s" in out
    assert not _left(marker), "the hanging test's processes outlived its timeout"

    p = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env,
                         start_new_session=True)
    try:
        deadline = time.monotonic() + 30
        while not _left(marker)[:1] and time.monotonic() < deadline:
            time.sleep(0.1)
        assert _left(marker), "the hanging test never started"
        os.kill(p.pid, signal.SIGKILL)
        p.wait(10)
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
    assert not _left(marker)
    deadline = time.monotonic() + 3
    while [c for c in _forked_tests() if str(tmp_path) in c] and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not [c for c in _forked_tests() if str(tmp_path) in c]
