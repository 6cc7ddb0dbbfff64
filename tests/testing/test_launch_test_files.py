"""Launch test files in the style of ros2/launch's launch_testing examples, run by `diffctl test`, by
`launch_test` (python -m launch_testing.launch_test) and by pytest: they pass and fail where launch_test would."""

from __future__ import annotations

import shutil
import subprocess
import sys
import textwrap
from pathlib import Path
from xml.etree import ElementTree as ET

import pytest

HERE = Path(__file__).resolve().parent
FILES = HERE / "launch_tests"
PY = sys.executable


def _run(argv: list[str], cwd: Path | None = None, timeout: float = 120) -> subprocess.CompletedProcess[str]:
    return subprocess.run(argv, capture_output=True, text=True, cwd=cwd, timeout=timeout, start_new_session=True)


def _cases(xml: Path) -> dict[str, str]:
    """'Class.method' → '' (passed) or the failure/error message."""
    out = {}
    for case in ET.parse(xml).getroot().iter("testcase"):
        key = case.get("classname", "").split(".")[-1] + "." + case.get("name", "")
        bad = case.find("failure")
        if bad is None:
            bad = case.find("error")
        out[key] = "" if bad is None else bad.get("message", "")
    return out


@pytest.mark.slow
def test_examples_pass_and_fail_where_launch_test_does(tmp_path: Path) -> None:
    xml = tmp_path / "results.xml"
    names = ("good_proc", "params", "hello_world", "talker_listener", "terminating_proc", "bad_proc", "stopped_early")
    files = [FILES / f"{n}_launch_test.py" for n in names]
    r = _run([PY, "-m", "diffctl", "test", *map(str, files), "-j", "2", "--junit-xml", str(xml), "dut_arg:=xyz"])
    assert r.returncode == 1, r.stdout + r.stderr
    cases = _cases(xml)
    failed = {k: v for k, v in cases.items() if v}
    assert set(failed) == {"TestBad.test_never_printed", "TestAfter.test_exit_codes", "TestWaits.test_waits_long"}
    assert "Waiting for output timed out" in failed["TestBad.test_never_printed"]
    assert "Proc bad-1 exited with code 1" in failed["TestAfter.test_exit_codes"]  # launch's process names
    assert "Launch stopped before the active tests finished." in failed["TestWaits.test_waits_long"]
    # every parametrized run, named as launch_testing names them
    for param in ("thing=On", "thing=Off", "flag1"):
        assert cases[f"TestProcessOutput.test_process_outputs_expected_value[{param}]"] == ""
        assert cases[f"TestAfter.test_arg_in_cmd[{param}]"] == ""  # dut_arg:=xyz reached the command line
    assert cases["TestProcessOutput.test_out_of_order"] == ""
    assert cases["TestHelloWorldShutdown.test_exit_codes"] == ""
    out = r.stdout
    assert "Processes under test stopped before tests completed" in out
    assert "Process 'short-1' exited with 3" in out and "hello_world" in out
    assert "Starting test run params_launch_test.params_launch_test.launch_tests[thing=Off]" in out
    assert "Summary: 7 test files, 5 passed, 2 failed" in out
    assert cases["TestTerminatingProc.test_unhandled_exception"] == ""  # launch_testing's example processes
    for name in ("test_talker_transmits", "test_listener_receives", "test_republished_data", "test_wait_for_topics"):
        assert cases[f"TestTalkerListenerLink.{name}"] == ""  # rclpy test bodies on the test's own bus
    assert "test_count_to_four (good_proc_launch_test.TestGoodProcess.test_count_to_four) ..." in out  # unittest's
    root = ET.parse(xml).getroot()
    logs = "".join(e.text or "" for e in root.iter("system-out"))
    assert "Loop 3" in logs and "Exiting with a code" in logs  # the processes' own logs


def test_launch_test_cli_exit_codes_and_show_args(tmp_path: Path) -> None:
    """launch_testing's own module (python -m) and diffctl's `launch_test` command: --show-args, and a file that
    cannot run is exit code 2 with one line saying why."""
    r = _run([PY, "-m", "launch_testing.launch_test", str(FILES / "params_launch_test.py"), "-s"])
    assert r.returncode == 0, r.stderr
    assert "Arguments (pass arguments as '<name>:=<value>'):" in r.stdout
    assert "'dut_arg':" in r.stdout and "(default: 'default')" in r.stdout
    launch_test = str(Path(PY).parent / "launch_test")
    r = _run([launch_test, str(FILES / "params_launch_test.py"), "oops"])
    assert r.returncode == 2
    assert "malformed launch argument 'oops', expected format '<name>:=<value>'" in r.stderr
    plain = tmp_path / "test_plain.py"
    plain.write_text("def test_x():\n    pass\n")
    r = _run([launch_test, str(plain)])
    assert r.returncode == 2 and "no generate_test_description() in this file" in r.stderr
    no_ready = tmp_path / "no_ready_launch_test.py"
    no_ready.write_text("import launch\n\ndef generate_test_description():\n    return launch.LaunchDescription([])\n")
    r = _run([launch_test, str(no_ready)])
    assert r.returncode == 2
    assert "must return a LaunchDescription containing a ReadyToTest action" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1, r.stderr


@pytest.mark.slow
def test_pytest_runs_launch_test_files(tmp_path: Path) -> None:
    for name in ("good_proc_launch_test.py", "bad_proc_launch_test.py", "counter.py", "exit_code_proc.py"):
        shutil.copy(FILES / name, tmp_path / name)
    (tmp_path / "test_plain.py").write_text("def test_plain():\n    assert 1 + 1 == 2\n")
    r = _run([PY, "-m", "pytest", "-p", "no:cacheprovider", "-q", "--junit-xml", str(tmp_path / "p.xml"), "."],
             cwd=tmp_path)
    assert r.returncode == 1, r.stdout + r.stderr
    assert "1 failed, 2 passed" in r.stdout
    assert "FAIL: bad_proc_launch_test.TestBad.test_never_printed" in r.stdout
    assert "FAIL: bad_proc_launch_test.TestAfter.test_exit_codes" in r.stdout


@pytest.mark.slow
def test_workspace_discovery_and_launch_folder_never_shadows_launch(tmp_path: Path) -> None:
    """Packages' test/ folders as colcon test finds them; a package's launch/ folder (the repository's too) is
    never taken for the `launch` module, whether pytest runs from the package root or the repository root."""
    ws = tmp_path / "ws"
    for pkg in ("robot_a", "robot_b"):
        root = ws / "src" / pkg
        (root / "test").mkdir(parents=True)
        (root / "launch").mkdir()
        (root / "launch" / "bringup.launch.py").write_text("# a launch file, not a module\n")
        (root / "package.xml").write_text(textwrap.dedent(f"""\
            <?xml version="1.0"?>
            <package format="3"><name>{pkg}</name><version>0.0.0</version><description>d</description>
            <maintainer email="a@b.c">a</maintainer><license>MIT</license>
            <test_depend>launch_testing</test_depend>
            <export><build_type>ament_python</build_type></export></package>
            """))
        shutil.copy(FILES / "hello_world_launch_test.py", root / "test" / f"test_{pkg}.launch.py")
    r = _run([PY, "-m", "diffctl", "test", "--packages-select", "robot_b"], cwd=ws)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "robot_b/test_robot_b.launch.py" in r.stdout and "robot_a" not in r.stdout
    assert "Summary: 1 test files, 1 passed, 0 failed" in r.stdout
    r = _run([PY, "-m", "diffctl", "test", "--packages-select", "robot_b", "robot_c"], cwd=ws)
    assert r.returncode == 2 and "no package 'robot_c'" in r.stderr and "robot_a" in r.stderr
    pkg_root = ws / "src" / "robot_a"
    r = _run([PY, "-m", "pytest", "-p", "no:cacheprovider", "-q", "test"], cwd=pkg_root)
    assert r.returncode == 0 and "1 passed" in r.stdout, r.stdout + r.stderr
    repo = HERE.parent.parent
    assert (repo / "launch").is_dir()
    r = _run([PY, "-m", "pytest", "-p", "no:cacheprovider", "-q", str(pkg_root / "test")], cwd=repo)
    assert r.returncode == 0 and "1 passed" in r.stdout, r.stdout + r.stderr
