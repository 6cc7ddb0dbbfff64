"""`ros2 <verb> …` for machines without ROS 2: each ros2 CLI verb diffctl has runs diffctl's command of that name.

Launch files and launch tests run `ExecuteProcess(cmd=['ros2', 'bag', 'record', …])`, `ros2 topic pub`,
`ros2 param set`, `ros2 control …`. diffctl's commands take the same verbs and arguments, so `ros2 X args` is
`diffctl X args`. A real `ros2` further on PATH (a sourced ROS 2) always wins: this command hands over to it,
so a venv activated after sourcing ROS does not hide the real CLI.
"""

from __future__ import annotations

import os
import sys
from collections.abc import MutableMapping
from pathlib import Path

# ros2cli's verbs that diffctl has a command for (same name, same arguments).
VERBS: dict[str, str] = {
    "bag": "Record and replay rosbag2 bags",
    "control": "ros2_control's controller manager commands",
    "interface": "Show message and service definitions",
    "launch": "Run a launch file",
    "lifecycle": "Get, set and list the states of managed nodes",
    "node": "List nodes and show their endpoints",
    "param": "Get, set, list, describe, dump and load parameters",
    "pkg": "List packages and where they are",
    "run": "Run a package's executable",
    "service": "List and call services",
    "topic": "List, echo, publish and measure topics",
}

# Text found in diffctl's own `ros2` scripts (the console script and the launch wrapper) and in no real one.
MARKER = "diffctl.cli.ros2"


def is_ours(path: Path) -> bool:
    try:
        with path.open("rb") as f:
            return MARKER.encode() in f.read(4096)
    except OSError:
        return False


def find_real_ros2(path_value: str | None = None) -> Path | None:
    """The first `ros2` on PATH that is not one of diffctl's (ros2cli's script of a sourced ROS 2), or None."""
    folders = (os.environ.get("PATH", "") if path_value is None else path_value).split(os.pathsep)
    for folder in folders:
        if not folder:
            continue
        candidate = Path(folder) / "ros2"
        if candidate.is_file() and os.access(candidate, os.X_OK) and not is_ours(candidate):
            return candidate
    return None


def put_ros2_on_path(env: MutableMapping[str, str]) -> Path | None:
    """Put diffctl's `ros2` first on `env`'s PATH unless a real one is there; the folder used, or None.

    Its own folder (not gz's) so that a machine with ROS 2 never sees it on a launch's PATH.
    """
    if find_real_ros2(env.get("PATH", "")) is not None:
        return None
    from diffctl.gz.path import bin_dir, put_first_on_path, write_wrapper

    folder = bin_dir().parent / "ros2-bin"
    write_wrapper(folder / "ros2", f"#!{sys.executable}\nfrom {MARKER} import main\nmain()\n")
    put_first_on_path(env, folder)
    return folder


def usage() -> str:
    width = max(len(v) for v in VERBS)
    lines = [f"  {verb:<{width}}  {text}" for verb, text in VERBS.items()]
    return "usage: ros2 <verb> [args]  (diffctl's ros2 CLI: each verb runs `diffctl <verb>`)\n\nverbs:\n" + "\n".join(
        lines
    )


def main(argv: list[str] | None = None) -> None:
    args = sys.argv[1:] if argv is None else list(argv)
    real = find_real_ros2()
    if real is not None:
        os.execv(real, [str(real), *args])
    if not args or args[0] in ("-h", "--help"):
        print(usage(), file=sys.stdout if args else sys.stderr)
        sys.exit(0 if args else 2)
    verb = args[0]
    if verb not in VERBS:
        from diffctl.errors import suggest

        hint = suggest(verb, list(VERBS))
        print(
            f"error: ros2 verb {verb!r} is not available without ROS 2{hint}; diffctl's ros2 has: {', '.join(VERBS)}",
            file=sys.stderr,
        )
        sys.exit(2)
    from diffctl.cli.main import main as diffctl_main

    diffctl_main(args)
