"""`diffctl run PKG EXE` and `Node(package, executable)` start a user's ament_python programs from the sources:
console_scripts entry points (`module:func`, `module:obj.method`, setup.py and setup.cfg), `scripts=` files,
with the package and its workspace neighbours importable after diffctl's overlay."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from diffctl.workspace.share_tree import OVERLAY
from tests.workspace.conftest import package_xml, write_tree

SETUP_PY = """from setuptools import setup
package_name = 'my_pkg'
setup(
    name=package_name,
    packages=[package_name],
    data_files=[('share/' + package_name, ['package.xml']),
                ('share/' + package_name + '/launch', ['launch/hello.launch.yaml'])],
    scripts=['scripts/tool.py'],
    entry_points={
        'console_scripts': [
            'hello = my_pkg.hello:main',
            'runner = my_pkg.hello:Runner.start',
            'crash = my_pkg.crash:main',
        ],
    },
)
"""

HELLO = """import sys
import my_lib.shared


def main():
    print('hello', my_lib.shared.VALUE, sys.argv[1:], flush=True)
    print('path', sys.path.index({overlay!r}) < sys.path.index({src!r}), flush=True)
    return 0


class Runner:
    @staticmethod
    def start():
        print('runner started', flush=True)
        return 3
"""

CRASH = """def fail(x):
    return 1 / x


def main():
    fail(0)
"""

TOOL = """#!/usr/bin/env python3
import sys
from my_pkg import hello
print('tool', __name__, sys.argv[1:], hello.__name__, flush=True)
"""

WAITER = """import time


def main():
    print('waiting', flush=True)
    try:
        time.sleep(30)
    except KeyboardInterrupt:
        print('interrupted', flush=True)
"""

SETUP_CFG_PKG = {
    "package.xml": package_xml("cfg_pkg", "ament_python"),
    "setup.py": "from setuptools import setup\nsetup()\n",
    "setup.cfg": "[options]\npackages = cfg_pkg\n[options.entry_points]\nconsole_scripts =\n"
    "    cfg_node = cfg_pkg.node:main\n",
    "cfg_pkg/__init__.py": "",
    "cfg_pkg/node.py": "def main():\n    print('cfg node ran', flush=True)\n",
}

LAUNCH = """launch:
- node: {pkg: my_pkg, exec: hello, name: hello, args: "a1"}
"""


@pytest.fixture
def ws(tmp_path: Path) -> Path:
    root = tmp_path / "ws"
    src = root / "src"
    write_tree(
        src / "my_pkg",
        {
            "package.xml": package_xml("my_pkg", "ament_python"),
            "setup.py": SETUP_PY,
            "resource/my_pkg": "",
            "my_pkg/__init__.py": "",
            "my_pkg/hello.py": HELLO.format(overlay=str(OVERLAY), src=str((src / "my_pkg").resolve())),
            "my_pkg/crash.py": CRASH,
            "scripts/tool.py": TOOL,
            "launch/hello.launch.yaml": LAUNCH,
        },
    )
    write_tree(
        src / "my_lib",
        {
            "package.xml": package_xml("my_lib", "ament_python"),
            "setup.py": "from setuptools import setup\nsetup(name='my_lib', packages=['my_lib'])\n",
            "my_lib/__init__.py": "",
            "my_lib/shared.py": "VALUE = 42\n",
        },
    )
    write_tree(src / "cfg_pkg", SETUP_CFG_PKG)
    return root


def run(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    return subprocess.run(
        [sys.executable, "-m", "diffctl", *args], capture_output=True, text=True, timeout=60, cwd=cwd, env=env
    )


def test_console_scripts_and_scripts_run_from_sources(ws: Path) -> None:
    r = run("run", "my_pkg", "hello", "x", "--flag", "--ros-args", "-p", "a:=1", cwd=ws)
    assert r.returncode == 0, r.stderr
    assert r.stdout.splitlines() == ["hello 42 ['x', '--flag', '--ros-args', '-p', 'a:=1']", "path True"]

    r = run("run", "my_pkg", "runner", cwd=ws)  # module:object.method, its return value is the exit code
    assert (r.returncode, r.stdout) == (3, "runner started\n")
    assert "[ros2run]: Process exited with failure 3" in r.stderr

    r = run("run", "my_pkg", "tool.py", "y", cwd=ws)  # scripts=[...], shebang on the system python
    assert r.returncode == 0, r.stderr
    assert r.stdout == "tool __main__ ['y'] my_pkg.hello\n"

    r = run("run", "cfg_pkg", "cfg_node", cwd=ws)  # setup.cfg [options.entry_points]
    assert (r.returncode, r.stdout) == (0, "cfg node ran\n"), r.stderr


def test_a_crash_shows_the_users_file_and_line_once(ws: Path) -> None:
    r = run("run", "my_pkg", "crash", cwd=ws)
    assert r.returncode == 1
    crash_py = str((ws / "src/my_pkg/my_pkg/crash.py").resolve())
    assert r.stderr.count("Traceback (most recent call last)") == 1
    assert f'File "{crash_py}", line 2, in fail' in r.stderr
    assert r.stderr.count("ZeroDivisionError: division by zero") == 1


def test_a_crash_under_launch_shows_the_traceback_once(ws: Path) -> None:
    (ws / "crash.launch.yaml").write_text("launch:\n- node: {pkg: my_pkg, exec: crash}\n")
    r = run("launch", "crash.launch.yaml", "--no-router", "--no-color", cwd=ws)
    out = r.stdout + r.stderr
    assert r.returncode != 0
    crash_py = str((ws / "src/my_pkg/my_pkg/crash.py").resolve())
    assert out.count("Traceback (most recent call last)") == 1
    assert out.count(f'File "{crash_py}", line 2, in fail') == 1


def test_wrong_names_list_close_matches(ws: Path) -> None:
    r = run("run", "my_pkgg", "hello", cwd=ws)
    assert r.returncode == 2
    assert "unknown package 'my_pkgg' (did you mean 'my_pkg'?)" in r.stderr
    r = run("run", "my_pkg", "helo", cwd=ws)
    assert r.returncode == 2
    assert "has no executable 'helo' (did you mean 'hello'?)" in r.stderr
    assert "crash, hello, runner, tool.py" in r.stderr


def test_a_launch_file_node_runs_the_same_program(ws: Path) -> None:
    r = run("launch", "my_pkg", "hello.launch.yaml", "--no-router", cwd=ws)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "hello 42 ['a1'" in r.stdout + r.stderr


def test_a_sigint_to_diffctl_run_alone_reaches_the_node(ws: Path) -> None:
    import signal
    import time

    write_tree(ws / "src/my_pkg", {"my_pkg/waiter.py": WAITER})
    setup = ws / "src/my_pkg/setup.py"
    setup.write_text(setup.read_text().replace("'crash = ", "'waiter = my_pkg.waiter:main', 'crash = "))
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    p = subprocess.Popen([sys.executable, "-m", "diffctl", "run", "my_pkg", "waiter"], cwd=ws, env=env,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        assert p.stdout.readline() == "waiting\n"
        started = time.monotonic()
        p.send_signal(signal.SIGINT)  # to `diffctl run` only, as `kill -INT` does
        out, err = p.communicate(timeout=10)
        assert time.monotonic() - started < 5
        assert (p.returncode, out) == (0, "interrupted\n"), err
    finally:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()


DEAF = """import signal
import time


def main():
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: print('ignored', signal.Signals(_[0]).name, flush=True))
    print('deaf', flush=True)
    while True:
        time.sleep(0.05)
"""


@pytest.mark.slow
def test_a_node_deaf_to_ctrl_c_is_stopped_as_launch_stops_it(ws: Path) -> None:
    """ros2 run waits forever on a node that ignores SIGINT; diffctl run escalates as diffctl launch (and ros2
    launch) does: SIGTERM 5 s after the Ctrl-C, SIGKILL 5 s after that, each step said."""
    import signal
    import time

    write_tree(ws / "src/my_pkg", {"my_pkg/deaf.py": DEAF})
    setup = ws / "src/my_pkg/setup.py"
    setup.write_text(setup.read_text().replace("'crash = ", "'deaf = my_pkg.deaf:main', 'crash = "))
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    p = subprocess.Popen([sys.executable, "-m", "diffctl", "run", "my_pkg", "deaf"], cwd=ws, env=env,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        assert p.stdout.readline() == "deaf\n"
        started = time.monotonic()
        os.killpg(p.pid, signal.SIGINT)  # a terminal's Ctrl-C: to the whole foreground group
        os.killpg(p.pid, signal.SIGINT)  # and a second one, which changes nothing
        out, err = p.communicate(timeout=60)
        took = time.monotonic() - started
        assert p.returncode == 128 + signal.SIGKILL, err
        assert err.splitlines() == ["[ros2run]: still running 5 s after SIGINT: sending SIGTERM",
                                    "[ros2run]: still running 5 s after SIGTERM: sending SIGKILL",
                                    "[ros2run]: Killed"], err
        assert out.count("ignored SIGINT") >= 1 and out.count("ignored SIGTERM") == 1, out
        assert 10.0 <= took < 30, took
    finally:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()
