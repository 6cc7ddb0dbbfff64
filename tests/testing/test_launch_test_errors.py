"""A launch test file that cannot run (a syntax error, a generate_test_description that raises) is one line naming
its file and line, exit code 2, with nothing left running (issue 28); a passing file beside them still passes,
forked from the shared zygote without a warning."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import psutil
import pytest

FILES = Path(__file__).resolve().parent / "launch_tests"
BROKEN = "import launch\n\n\ndef generate_test_description(:\n    return launch.LaunchDescription([])\n"
RAISES = """\
import launch
import launch_testing.actions


def robot():
    raise ValueError("no robot here")


def generate_test_description():
    robot()
    return launch.LaunchDescription([launch_testing.actions.ReadyToTest()])
"""


@pytest.mark.slow
def test_files_that_cannot_run_are_one_line_and_exit_2(tmp_path: Path) -> None:
    (tmp_path / "broken_launch_test.py").write_text(BROKEN)
    (tmp_path / "raises_launch_test.py").write_text(RAISES)
    (tmp_path / "hello_world_launch_test.py").write_text((FILES / "hello_world_launch_test.py").read_text())
    r = subprocess.run([sys.executable, "-m", "diffctl", "test", "-j", "2", "broken_launch_test.py",
                        "raises_launch_test.py", "hello_world_launch_test.py"], cwd=tmp_path, capture_output=True,
                       text=True, timeout=120, start_new_session=True)
    out = r.stdout + r.stderr
    assert r.returncode == 2, out
    assert f"launch_test: error: {tmp_path}/broken_launch_test.py:4: SyntaxError: " in out
    assert "launch_test: error: raises_launch_test.py:6: ValueError: no robot here" in out
    assert "hello_world_launch_test.py: passed" in out
    assert "Traceback" not in out and "RuntimeWarning" not in out
    assert not [p for p in psutil.process_iter(["cmdline"]) if str(tmp_path) in " ".join(p.info["cmdline"] or [])]
    # launch_test itself: the error is all of stderr
    r = subprocess.run([str(Path(sys.executable).parent / "launch_test"), "raises_launch_test.py"], cwd=tmp_path,
                       capture_output=True, text=True, timeout=60, start_new_session=True)
    assert r.returncode == 2
    assert r.stderr.strip().splitlines() == ["launch_test: error: raises_launch_test.py:6: ValueError: no robot here"]
