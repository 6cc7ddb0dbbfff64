"""launch_pytest files as its examples write them, run by pytest through diffctl's plugin (and by diffctl test)."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

FILES = Path(__file__).resolve().parent / "launch_tests"


@pytest.mark.slow
def test_launch_pytest_examples(tmp_path: Path) -> None:
    shutil.copy(FILES / "pytest_hello_world.py", tmp_path / "test_hello_world.py")
    shutil.copy(FILES / "pytest_module_scope.py", tmp_path / "test_module_scope.py")
    shutil.copy(FILES / "talker.py", tmp_path / "talker.py")
    r = subprocess.run([sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "test_module_scope.py", "-v"],
                       cwd=tmp_path, capture_output=True, text=True, timeout=120, start_new_session=True)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "keep_alive_launch[one][shutdown_test] PASSED" in r.stdout and "test_order PASSED" in r.stdout
    r = subprocess.run([sys.executable, "-m", "diffctl", "test", "test_hello_world.py", "--junit-xml", "r.xml"],
                       cwd=tmp_path, capture_output=True, text=True, timeout=120, start_new_session=True)
    assert r.returncode == 1, r.stdout + r.stderr
    assert "1 failed, 4 passed" in r.stdout
    assert "FAILED test_hello_world.py::test_fails_on_purpose" in r.stdout
    assert "AssertionError: 'tock' not in the output" in r.stdout
    xml = (tmp_path / "r.xml").read_text()
    assert "test_check_if_msgs_published" in xml and "test_after_shutdown" in xml
