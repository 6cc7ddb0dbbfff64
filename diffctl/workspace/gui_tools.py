"""GUI-only ROS tools named in launch files: mapped to diffctl's counterpart, or warned about and stood in for.

A launch file that starts `rqt_graph` or `joint_state_publisher_gui` next to the robot must still bring the
robot up. Tools with a counterpart start it (joint_state_publisher_gui → diffctl's joint_state_publisher,
which publishes /joint_states as the GUI does, its positions set by the visualizer's Joint Sliders panel
through the `source_list` topic /joint_sliders; rqt_robot_steering → the visualizer's teleop panel; rqt_topic → its
topics panel). Others are replaced by a stand-in process that says once what was skipped and then idles
until the launch ends, so `OnProcessExit(target_action=rqt…, on_exit=Shutdown())` does not fire early.
"""

from __future__ import annotations

import os
import shlex
import signal
import sys

# (package, executable) → (diffctl subcommand and arguments, what the user gets instead)
MAPPED: dict[tuple[str, str], tuple[tuple[str, ...], str]] = {
    ("joint_state_publisher_gui", "joint_state_publisher_gui"): (
        ("joint-state-publisher", "--ros-args", "-p", "source_list:=[/joint_sliders]", "--"),
        "diffctl's joint_state_publisher publishes /joint_states from the sliders of the visualizer's "
        "Joint Sliders panel (topic /joint_sliders)",
    ),
    ("rqt_robot_steering", "rqt_robot_steering"): (
        ("viz", "--port", "0"),
        "steering: the visualizer's teleop panel (its URL is printed below)",
    ),
    ("rqt_topic", "rqt_topic"): (("viz", "--port", "0"), "topic monitor: the visualizer's topics panel"),
}
KEEP_ARGUMENTS = frozenset({"joint_state_publisher_gui"})
# GUI-only packages without a counterpart: stood in for, with one warning.
GUI_ONLY_PACKAGES = frozenset({"rqt", "rqt_gui", "plotjuggler", "rqt_gui_py", "rqt_gui_cpp"})


def is_gui_only(package: str) -> bool:
    return package.startswith("rqt_") or package in GUI_ONLY_PACKAGES


def argv_for(package: str, executable: str) -> list[str] | None:
    """The command that stands in for a GUI-only tool, or None when `package` is not one."""
    mapped = MAPPED.get((package, executable))
    if mapped is not None:
        sub, note = mapped
        # the counterpart's command is one word: what the launch appends (arguments, --ros-args …) follows it
        return [
            sys.executable,
            "-m",
            "diffctl.workspace.gui_tools",
            "--run",
            package,
            executable,
            note,
            shlex.join(sub),
        ]
    if is_gui_only(package):
        return [sys.executable, "-m", "diffctl.workspace.gui_tools", "--skip", package, executable]
    return None


def ros_args_only(argv: list[str]) -> list[str]:
    """The `--ros-args … [--]` spans of `argv` (remappings, parameters, the node name), nothing else."""
    out: list[str] = []
    inside = False
    for word in argv:
        if word == "--ros-args":
            inside = True
        elif inside and word == "--":
            inside = False
        if inside or word == "--ros-args":
            out.append(word)
    return out


def _stand_in(package: str, executable: str) -> int:
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: sys.exit(0))
    print(
        f"[WARN] {package}/{executable} is a GUI-only tool diffctl does not provide; skipped "
        "(the rest of the launch runs; `diffctl viz` shows the robot, TF, topics and a teleop panel)",
        file=sys.stderr,
        flush=True,
    )
    while True:
        signal.pause()


def main(argv: list[str]) -> int:
    if argv[:1] == ["--skip"] and len(argv) >= 3:
        return _stand_in(argv[1], argv[2])
    if argv[:1] == ["--run"] and len(argv) >= 5:
        package, executable, note, sub = argv[1:5]
        print(f"[INFO] {package}/{executable} runs as diffctl's counterpart: {note}", file=sys.stderr, flush=True)
        # The tool's own arguments (rqt_topic -t, …) mean nothing to the counterpart, except for
        # joint_state_publisher_gui, whose description-file argument joint_state_publisher takes too.
        rest = argv[5:] if package in KEEP_ARGUMENTS else ros_args_only(argv[5:])
        # exec: the process the launch watches becomes the counterpart itself
        os.execv(sys.executable, [sys.executable, "-m", "diffctl", *shlex.split(sub), *rest])
    print("usage: python -m diffctl.workspace.gui_tools --skip PKG EXE | --run PKG EXE NOTE 'SUBCOMMAND …' [ARGS…]")
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
