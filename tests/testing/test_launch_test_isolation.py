"""Launch tests run side by side on buses of their own; a hanging one is stopped with everything it started."""

from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import sys
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
    assert took < 2 * 3.0 + 8  # side by side: each listens 3 s


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
    assert took < 15
    left = _left(marker)
    assert not left, [p.info["cmdline"] for p in left]


def _left(marker: str) -> list[psutil.Process]:
    deadline = time.monotonic() + 3
    while True:
        left = [p for p in psutil.process_iter(["cmdline"]) if marker in " ".join(p.info["cmdline"] or [])]
        if not left or time.monotonic() > deadline:
            return left
        time.sleep(0.1)


@pytest.mark.slow
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGKILL], ids=["ctrl-c", "killed"])
def test_stopping_diffctl_test_stops_its_tests_and_their_processes(sig: int) -> None:
    """Ctrl-C (exit 130), or diffctl test killed outright (a cancelled CI job): nothing it started is left."""
    marker = f"{5000 + uuid.uuid4().int % 1000}.{uuid.uuid4().int % 9 + 1}"
    env = {**os.environ, "HANG_MARKER": marker}
    p = subprocess.Popen([sys.executable, "-m", "diffctl", "test", str(FILES / "hanging_launch_test.py")],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env,
                         start_new_session=True)
    try:
        deadline = time.monotonic() + 20
        while not _left(marker)[:1] and time.monotonic() < deadline:
            time.sleep(0.1)
        assert _left(marker), "the hanging test never started"
        os.kill(p.pid, sig)
        code = p.wait(10)
        assert code == (130 if sig == signal.SIGINT else -signal.SIGKILL)
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
        p.stdout.close()
    left = _left(marker)
    assert not left, [q.info["cmdline"] for q in left]
