"""What a user sees when their node fails: a callback's exception out of spin with their own file and line,
exactly as under the real rclpy; a node started with no router says so in one line and exits 2."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time

import pytest

from bench.ports import free_port
from tests.client.differential import PROGRAMS, REPO
from tests.conftest import Procs
from tests.oracle import jazzy_venv


def _user_frames(stderr: str) -> list[str]:
    """The traceback's last line and the frames in the user's program (paths differ between the runs)."""
    lines = stderr.splitlines()
    frames = [ln.strip() for i, ln in enumerate(lines) if (ln.strip().startswith("File") and "raises.py" in ln)
              or (i > 0 and "raises.py" in lines[i - 1] and ln.startswith("    ") and not ln.strip().startswith("^"))]
    return [f.split(", ", 1)[-1] for f in frames] + lines[-1:]


def test_callback_exception_propagates_with_the_users_traceback(router: str) -> None:
    ours = subprocess.run([sys.executable, str(PROGRAMS / "raises.py")], capture_output=True, text=True, timeout=30,
                          cwd=REPO)
    assert ours.returncode == 1
    assert ours.stderr.count("Traceback (most recent call last)") == 1
    assert ours.stderr.strip().splitlines()[-1] == "KeyError: 'missing'"
    # The real rclpy, the program run from a file of the same name: the same frames of the user's code.
    real_dir = jazzy_venv.VENV.parent / "test-output" / "client_raises"
    real_dir.mkdir(parents=True, exist_ok=True)
    program = real_dir / "raises.py"
    program.write_text((PROGRAMS / "raises.py").read_text())
    real = subprocess.run([str(jazzy_venv.python()), "-I", str(program)], env=jazzy_venv.env(), capture_output=True,
                          text=True, timeout=60)
    assert real.returncode == 1
    assert _user_frames(ours.stderr) == _user_frames(real.stderr)
    assert any("line 8, in broken_callback" in f for f in _user_frames(ours.stderr))


def test_no_router_is_one_line_and_exit_2() -> None:
    endpoint = f"tcp/127.0.0.1:{free_port()}"  # nothing listens there
    p = subprocess.run([sys.executable, str(PROGRAMS / "raises.py")], capture_output=True, text=True, timeout=30,
                       env={**os.environ, "DIFFCTL_ROUTER": endpoint}, cwd=REPO)
    assert p.returncode == 2
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1, p.stderr
    assert endpoint in lines[0] and "diffctl router" in lines[0]


def _signal_outcome(p: subprocess.Popen, sig: int) -> tuple[int, str]:
    assert p.stdout.readline().strip() == "spinning"
    time.sleep(0.5)
    p.send_signal(sig)
    _, err = p.communicate(timeout=20)
    lines = err.strip().splitlines()
    return p.returncode, lines[-1] if lines else ""


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_signals_end_spin_as_in_rclpy(router: str, procs: Procs, sig: int) -> None:
    """Ctrl-C: KeyboardInterrupt out of spin; SIGTERM: ExternalShutdownException — the exit and the last line the
    real rclpy gives. (The real one races on SIGTERM: a context shut down between two waits lets spin return
    normally now and then, or rcl_wait raises RCLError; diffctl always reports the external shutdown. On Ctrl-C
    under load its KeyboardInterrupt now and then lands inside the Task rclpy builds for the due timer, and its
    last line is then that half-built Task's __del__ failing, `'Task' object has no attribute '_exception'`.)"""
    code = (PROGRAMS / "spin_forever.py").read_text()
    real = procs.start([str(jazzy_venv.python()), "-I", "-c", code], env=jazzy_venv.env(), stderr=subprocess.PIPE)
    ours = procs.start([sys.executable, str(PROGRAMS / "spin_forever.py")], stderr=subprocess.PIPE)
    real_outcome, our_outcome = _signal_outcome(real, sig), _signal_outcome(ours, sig)
    if sig == signal.SIGINT:
        assert our_outcome == (-signal.SIGINT, "KeyboardInterrupt")
        assert real_outcome == our_outcome or (
            real_outcome[0] == -signal.SIGINT and "'Task' object has no attribute '_exception'" in real_outcome[1]
        ), real_outcome
    else:
        assert our_outcome == (1, "rclpy.executors.ExternalShutdownException")
        # The real one's race has a third outcome: the context is shut down inside rcl_wait, which raises RCLError.
        assert real_outcome == our_outcome or real_outcome[0] == 0 or "RCLError" in real_outcome[1], real_outcome


def test_sigterm_ends_a_multithreaded_spin_quietly(router: str, procs: Procs) -> None:
    """rclpy's MultiThreadedExecutor swallows the external shutdown: rclpy.spin returns, exit 0 (ros2/examples'
    minimal_action_server then fails only in its own rclpy.shutdown()), and a line logged afterwards is
    followed by rcl's rosout handler refusing the signal-shut context on stderr (not once the node is gone)."""
    code = (PROGRAMS / "spin_forever.py").read_text()
    real = procs.start([str(jazzy_venv.python()), "-I", "-c", code, "multi"], env=jazzy_venv.env(),
                       stderr=subprocess.PIPE)
    ours = procs.start([sys.executable, str(PROGRAMS / "spin_forever.py"), "multi"], stderr=subprocess.PIPE)
    stamp = re.compile(r"\[\d+\.\d{9}\] ")
    outcomes = []
    for p in (real, ours):
        assert p.stdout.readline().strip() == "spinning"
        time.sleep(0.5)
        p.send_signal(signal.SIGTERM)
        _, err = p.communicate(timeout=20)
        outcomes.append((p.returncode, [stamp.sub("", ln) for ln in err.splitlines() if "[rcl]" not in ln]))
    expected = (0, ["[INFO] [spinner]: spin returned", "Failed to publish log message to rosout: publisher's context "
                    "is invalid, at /project/src/rcl/publisher.c:423",
                    "[INFO] [spinner]: node destroyed"])  # a destroyed node has no /rosout publisher to refuse
    assert outcomes[1] == expected
    # The real one's race: the context shut down inside rcl_wait raises RCLError out of the pool's wait.
    assert outcomes[0] == expected or "RCLError" in "".join(outcomes[0][1]), outcomes[0]


@pytest.mark.parametrize("env", [{"RCUTILS_COLORIZED_OUTPUT": "1"},
                                 {"RCUTILS_CONSOLE_OUTPUT_FORMAT": "{severity} {name} {function_name}:{line_number} "
                                                                   "{message}", "RCUTILS_COLORIZED_OUTPUT": "0"}])
def test_console_lines_as_rclpy(env: dict[str, str]) -> None:
    """The same console lines, byte for byte but the stamps, under both (colours and the format variable)."""
    stamp = re.compile(r"\[\d+\.\d{9}\]")
    code = (PROGRAMS / "console.py").read_text()
    real = jazzy_venv.run_python(code, env_extra=env)
    ours = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=30,
                          env={**os.environ, **env}, cwd=REPO)
    assert ours.returncode == 0, ours.stderr
    assert ours.stdout == real.stdout
    real_lines = [stamp.sub("[T]", ln) for ln in real.stderr.splitlines() if "[rcl]" not in ln]
    assert [stamp.sub("[T]", ln) for ln in ours.stderr.splitlines()] == real_lines
