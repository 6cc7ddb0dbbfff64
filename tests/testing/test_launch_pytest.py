"""launch_pytest files as its examples write them, run by pytest through diffctl's plugin (here via diffctl test)."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path
from xml.etree import ElementTree as ET

import pytest

FILES = Path(__file__).resolve().parent / "launch_tests"


@pytest.mark.slow
def test_launch_pytest_examples(tmp_path: Path) -> None:
    shutil.copy(FILES / "pytest_hello_world.py", tmp_path / "test_hello_world.py")
    shutil.copy(FILES / "pytest_module_scope.py", tmp_path / "test_module_scope.py")
    shutil.copy(FILES / "pytest_after_the_fact.py", tmp_path / "test_after_the_fact.py")
    shutil.copy(FILES / "talker.py", tmp_path / "talker.py")
    r = subprocess.run([sys.executable, "-m", "diffctl", "test", "test_hello_world.py", "test_module_scope.py",
                        "test_after_the_fact.py", "-j", "2", "--junit-xml", "r.xml"],
                       cwd=tmp_path, capture_output=True, text=True, timeout=120, start_new_session=True)
    assert r.returncode == 1, r.stdout + r.stderr
    assert "1 failed, 4 passed" in r.stdout  # test_hello_world.py
    assert "FAILED test_hello_world.py::test_fails_on_purpose" in r.stdout
    assert "AssertionError: 'tock' not in the output" in r.stdout
    assert "test_module_scope.py: passed" in r.stdout
    assert "test_after_the_fact.py: passed" in r.stdout  # waits for a start or exit that already happened
    cases = {c.get("name"): c.find("failure") is None for c in ET.parse(tmp_path / "r.xml").getroot().iter("testcase")}
    assert cases["test_check_if_msgs_published"] and cases["test_after_shutdown"] and cases["test_read_stdout"]
    # the module-scoped launch: shutdown=True tests last, the parts after yield in items of their own, in order
    # the twins are named test_up[one][shutdown_test] by pytest 7, test_up[shutdown_test][one] by pytest 9
    twins = {name: ok for name, ok in cases.items() if "[shutdown_test]" in name}
    assert len(twins) == 2 and all(twins.values()) and {"one", "two"} == {n.split("[")[-1][:3] for n in twins}
    assert cases["test_order"]
