"""`diffctl run PKG EXE [args] [--ros-args …]`: the `ros2 run` counterpart.

The executable resolves as `Node(package, executable)` does in a launch file (one path,
`diffctl.workspace.package_index.executable_argv`): a workspace package's console scripts and installed
scripts run from its sources without building, with diffctl's overlay (rclpy, tf2_ros, …) and the
workspace's Python packages importable; then diffctl's components; then install trees.
"""

from __future__ import annotations

import shlex
import signal
import subprocess
import sys
from pathlib import Path

import click

SIGINT_GRACE_S = 1.0


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
    """Run `command` in this process group (a terminal's Ctrl-C reaches it directly) until it exits;
    a SIGTERM sent to us is passed on, and so is a SIGINT sent to us alone (`kill -INT`, a supervisor)
    when the child is still running a moment later. Non-zero exits are reported as ros2 run does."""
    try:
        process = subprocess.Popen(command)
    except OSError as e:
        from diffctl.errors import LaunchError

        raise LaunchError(f"cannot start {command[0]}: {e.strerror}") from None
    previous = signal.signal(signal.SIGTERM, lambda signum, frame: process.send_signal(signum))
    try:
        while process.returncode is None:
            try:
                process.wait()
            except KeyboardInterrupt:
                # From a terminal the child has the same SIGINT and decides itself how to end.
                try:
                    process.wait(SIGINT_GRACE_S)
                except subprocess.TimeoutExpired:
                    process.send_signal(signal.SIGINT)
                except KeyboardInterrupt:
                    pass
    finally:
        signal.signal(signal.SIGTERM, previous)
    code = process.returncode
    if code < 0:
        print(f"[ros2run]: {signal.strsignal(-code)}", file=sys.stderr, flush=True)
        return 128 - code
    if code != 0:
        print(f"[ros2run]: Process exited with failure {code}", file=sys.stderr, flush=True)
    return code


__all__ = ["run"]
