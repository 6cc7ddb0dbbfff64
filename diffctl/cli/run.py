"""`diffctl run PKG EXE [args] [--ros-args …]`: the `ros2 run` counterpart.

The executable resolves as `Node(package, executable)` does in a launch file (one path,
`diffctl.workspace.package_index.executable_argv`): a workspace package's console scripts and installed
scripts run from its sources without building, with diffctl's overlay (rclpy, tf2_ros, …) and the
workspace's Python packages importable; then diffctl's components; then install trees.
"""

from __future__ import annotations

import os
import shlex
import signal
import subprocess
import sys
import threading
from pathlib import Path

import click

# A SIGINT sent to this command alone (`kill -INT`, a supervisor) is passed on when the child, which did not get
# it from a terminal, is still running this long after. A child that did get it (a Ctrl-C, a signal to the group)
# may still be exiting then on a loaded machine — a client program's exit joins Zenoh's threads — and a second
# SIGINT cuts that exit short (seen at 1 s: the node had stopped cleanly, then died of the second one, exit 130).
# Then, as diffctl launch does (launch's sigterm_timeout and sigkill_timeout), a child still running escalates to
# SIGTERM and SIGKILL, each step said.
SIGINT_GRACE_S = 2.5
SIGTERM_TIMEOUT_S = 5.0
SIGKILL_TIMEOUT_S = 5.0


@click.command(context_settings={"ignore_unknown_options": True, "allow_interspersed_args": False})
@click.option(
    "--workspace",
    "workspace_dir",
    type=click.Path(file_okay=False, path_type=Path),
    default=None,
    help="The workspace to use (default: $DIFFCTL_WORKSPACE, else the one enclosing the current directory).",
)
@click.option("--prefix", default=None, help="Prefix command, e.g. 'gdb -ex run --args' (as ros2 run --prefix).")
@click.argument("package")
@click.argument("executable")
@click.argument("argv", nargs=-1, type=click.UNPROCESSED)
def run(workspace_dir: Path | None, prefix: str | None, package: str, executable: str, argv: tuple[str, ...]) -> int:
    """Run EXECUTABLE of PACKAGE with ARGV and any --ros-args (ros2 run).

    \b
    Example:
      diffctl run my_pkg avoider --ros-args -p speed:=0.3 -r cmd_vel:=/diffbot_base_controller/cmd_vel
      diffctl run demo_nodes_py talker
    """
    from diffctl import ros_args
    from diffctl.workspace import find_workspace, use_in_children
    from diffctl.workspace.package_index import executable_argv

    use_in_children(find_workspace(explicit=workspace_dir))
    command = executable_argv(package, executable) + list(argv)
    ros = ros_args.current_argv()
    if ros:
        command += ["--ros-args", *ros]
    if prefix:
        command = shlex.split(prefix) + command
    return _supervise(command)


def _supervise(command: list[str]) -> int:
    """Run `command` in this process group (a terminal's Ctrl-C reaches it directly) until it exits. A SIGTERM
    sent to us is passed on, and so is a SIGINT sent to us alone (`kill -INT`, a supervisor) when the child is
    still running a moment later; a child that outlives the stop escalates (`_stop_steps`). Non-zero exits are
    reported as ros2 run does."""
    from diffctl.workspace.program_exit import REPORT_FD_ENV

    # A program started from a workspace's sources says here, not on its stderr, that the input it read was bad
    # (diffctl.workspace.program_exit): this command then reports it once, as its own error.
    report_r, report_w = os.pipe()
    try:
        process = subprocess.Popen(command, pass_fds=(report_w,), env={**os.environ, REPORT_FD_ENV: str(report_w)})
    except OSError as e:
        from diffctl.errors import LaunchError

        os.close(report_r)
        raise LaunchError(f"cannot start {command[0]}: {e.strerror}") from None
    finally:
        os.close(report_w)
    stopping = _Stopper(process)
    previous = {sig: signal.signal(sig, stopping.on_signal) for sig in (signal.SIGINT, signal.SIGTERM)}
    try:
        while process.returncode is None:
            process.wait()
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        stopping.done.set()
    code = process.returncode
    bad_input = _read_report(report_r)
    if bad_input and code == 2:
        from diffctl.errors import ConfigError

        raise ConfigError(bad_input)
    if code < 0:
        print(f"[ros2run]: {signal.strsignal(-code)}", file=sys.stderr, flush=True)
        return 128 - code
    if code != 0:
        print(f"[ros2run]: Process exited with failure {code}", file=sys.stderr, flush=True)
    return code


def _stop_steps(first: int) -> list[tuple[float, int, str]]:
    """(seconds after the first stop signal, signal to send, what to say) until the child is surely gone."""
    if first == signal.SIGTERM:
        return [(0.0, signal.SIGTERM, ""),
                (SIGKILL_TIMEOUT_S, signal.SIGKILL, f"still running {SIGKILL_TIMEOUT_S:g} s after SIGTERM")]
    return [(SIGINT_GRACE_S, signal.SIGINT, ""),
            (SIGTERM_TIMEOUT_S, signal.SIGTERM, f"still running {SIGTERM_TIMEOUT_S:g} s after SIGINT"),
            (SIGTERM_TIMEOUT_S + SIGKILL_TIMEOUT_S, signal.SIGKILL,
             f"still running {SIGKILL_TIMEOUT_S:g} s after SIGTERM")]


class _Stopper:
    """From the first stop signal on, a thread sends the child the rest of `_stop_steps` while it runs. A later
    SIGTERM is passed on at once; a later Ctrl-C changes nothing (the schedule is already running)."""

    def __init__(self, process: subprocess.Popen) -> None:
        self.process = process
        self.done = threading.Event()  # the child was reaped
        self.thread: threading.Thread | None = None

    def on_signal(self, signum: int, frame: object) -> None:
        if self.thread is None:
            self.thread = threading.Thread(target=self._escalate, args=(_stop_steps(signum),), daemon=True,
                                           name="ros2run-stop")
            self.thread.start()
        elif signum == signal.SIGTERM:
            self.process.send_signal(signum)

    def _escalate(self, steps: list[tuple[float, int, str]]) -> None:
        waited = 0.0
        for after_s, sig, why in steps:
            if self.done.wait(after_s - waited) or self.process.poll() is not None:
                return
            waited = after_s
            if why:
                print(f"[ros2run]: {why}: sending {signal.Signals(sig).name}", file=sys.stderr, flush=True)
            self.process.send_signal(sig)


def _read_report(fd: int) -> str:
    """What the program wrote to the report pipe (nothing when it did not; a child it left behind may still
    hold the pipe open, so the read never waits)."""
    os.set_blocking(fd, False)
    try:
        return os.read(fd, 65536).decode("utf-8", "replace").strip()
    except BlockingIOError:
        return ""
    finally:
        os.close(fd)


__all__ = ["run"]
