"""The package index: `Node(package, executable)` → a command line, `$(find-pkg-share pkg)` → a directory.

Share directories come from `diffctl.workspace` (the user's workspace, install trees, diffctl's own
packages, in that order). diffctl's own components stand under the ROS names they replace and start as
`python -m diffctl …`; a package of the user's workspace or an install tree starts its `lib/<pkg>/<exe>`, in
diffctl's graph over rmw_zenoh (ros_programs.py).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

from diffctl import workspace
from diffctl.errors import LaunchError, suggest
from diffctl.workspace import builtin, ros_programs

# (package, executable) → diffctl subcommand
COMPONENTS: dict[tuple[str, str], tuple[str, ...]] = {
    ("robot_state_publisher", "robot_state_publisher"): ("robot-state-publisher",),
    ("joint_state_publisher", "joint_state_publisher"): ("joint-state-publisher",),
    ("controller_manager", "ros2_control_node"): ("control", "manager"),
    ("controller_manager", "spawner"): ("spawn", "controller"),
    ("ros_gz_sim", "gz_sim"): ("sim", "run"),
    ("ros_gz_sim", "create"): ("spawn", "entity"),
    ("ros_gz_bridge", "parameter_bridge"): ("bridge",),
    ("ros_gz_image", "image_bridge"): ("image-bridge",),
    ("rviz2", "rviz2"): ("viz",),
    ("teleop_twist_joy", "teleop_node"): ("teleop-twist-joy",),
    ("teleop_twist_keyboard", "teleop_twist_keyboard"): ("teleop-twist-keyboard",),
    ("foxglove_bridge", "foxglove_bridge"): ("foxglove-bridge",),
    ("tf2_ros", "static_transform_publisher"): ("tf2", "static_transform_publisher"),
    ("tf2_ros", "tf2_echo"): ("tf2", "tf2_echo"),
    ("diffctl", "router"): ("router",),
    ("robot_localization", "ekf_node"): ("robot-localization", "ekf_node"),
    ("robot_localization", "ukf_node"): ("robot-localization", "ukf_node"),
    ("robot_localization", "navsat_transform_node"): ("robot-localization", "navsat_transform_node"),
    **{("topic_tools", exe): ("topic-tools", exe)
       for exe in ("relay", "throttle", "drop", "delay", "mux", "demux", "relay_field")},
    ("twist_mux", "twist_mux"): ("twist-mux",),
    ("joy_teleop", "joy_teleop"): ("joy-teleop",),
    ("joy", "joy_node"): ("joy", "joy_node"),
    ("key_teleop", "key_teleop"): ("key-teleop",),
    ("interactive_marker_twist_server", "marker_server"): ("interactive-marker-twist-server",),
    ("laser_filters", "scan_to_scan_filter_chain"): ("laser-filters", "scan_to_scan_filter_chain"),
    ("joy_linux", "joy_linux_node"): ("joy-linux", "joy_linux_node"),
    **{("ros2_controllers_test_nodes", exe): ("ros2-controllers-test-nodes", exe)
       for exe in ("publisher_forward_position_controller", "publisher_joint_trajectory_controller")},
    ("twist_stamper", "twist_stamper"): ("twist-stamper", "twist_stamper"),
    ("twist_stamper", "twist_unstamper"): ("twist-stamper", "twist_unstamper"),
    # Containers of composable nodes: Python components in one process, loaded over its load_node service
    ("rclcpp_components", "component_container"): ("component-container",),
    ("rclcpp_components", "component_container_mt"): ("component-container", "--multi-threaded"),
    ("rclcpp_components", "component_container_isolated"): ("component-container", "--multi-threaded"),
}

LAUNCH_SUFFIXES = (".yaml", ".launch.yaml", ".launch.py", ".launch.xml", ".xml")

# Share directories of component packages (launch files written for ROS include them, e.g. gz_sim.launch.py).
COMPONENT_SHARES = builtin.COMPONENT_SHARES


def project_root() -> Path:
    """The top of the project: the checkout holding diffctl/, or diffctl/share in an installed wheel."""
    return builtin.project_root()


def project_packages() -> dict[str, Path]:
    return builtin.builtin_packages()


def component_packages() -> set[str]:
    return {pkg for pkg, _ in COMPONENTS}


def known_packages() -> list[str]:
    from diffctl import demo_nodes

    return sorted({p.name for p in workspace.list_packages()} | component_packages() | set(demo_nodes.PACKAGES))


_reported: set[str] = set()


def share_dir(package: str) -> Path:
    """The share directory of `package`, as ament_index's get_package_share_directory gives it. Install
    rules of a workspace package that install nothing are reported once: a file the launch file then
    opens would otherwise be missing without a word."""
    try:
        found = workspace.find_package(package)
    except workspace.PackageNotFoundError:
        if package not in component_packages():
            raise
    else:
        if found.problems and package not in _reported:
            from diffctl.console import warn

            _reported.add(package)
            for problem in found.problems:
                warn(f"package {package!r} ({found.source}): {problem}")
        return found.share
    raise LaunchError(
        f"package {package!r} is a diffctl component with no share directory",
        hint=f"start it with Node(package={package!r}, executable=…)",
    )


def _lib_dir(package: str, *, workspace_only: bool = False) -> Path | None:
    """`<prefix>/lib/<package>` of a workspace (or, unless `workspace_only`, installed) package."""
    try:
        found = workspace.find_package(package)
    except LaunchError:
        return None
    if found.prefix is None or (workspace_only and found.origin != "workspace"):
        return None
    lib = found.prefix / "lib" / package
    return lib if lib.is_dir() else None


def _program(lib: Path | None, executable: str) -> Path | None:
    candidate = lib / executable if lib is not None else None
    return candidate if candidate is not None and candidate.is_file() and os.access(candidate, os.X_OK) else None


def _built_program(package: str, executable: str) -> Path | None:
    """A workspace package's program as colcon built it: `install/<pkg>/lib/<pkg>/<exe>` (isolated) or
    `install/lib/<pkg>/<exe>` (merged) of the workspace, or of an install on the prefix paths (a sourced
    install/setup.bash). Its sources stay the package's share; the built program is what runs."""
    try:
        found = workspace.find_package(package)
    except LaunchError:
        return None
    if found.origin != "workspace":
        return None
    roots = []
    ws = workspace.find_workspace()
    if ws is not None:
        roots += [ws / "install" / package, ws / "install"]
    from diffctl.workspace import prefixes

    roots += [p.path for p in prefixes.install_prefixes()]
    for root in roots:
        program = _program(root / "lib" / package, executable)
        if program is not None:
            return program
    return None


def _compiled_program(package: str, executable: str) -> str | None:
    """`CMakeLists.txt:N` where a workspace package declares `add_executable(<executable> …)`, else None."""
    import re

    try:
        found = workspace.find_package(package)
    except LaunchError:
        return None
    cmake = found.source / "CMakeLists.txt" if found.source is not None else None
    if cmake is None or not cmake.is_file():
        return None
    declared = re.compile(r"^\s*add_executable\s*\(\s*" + re.escape(executable) + r"[\s)]", re.IGNORECASE)
    for number, line in enumerate(cmake.read_text(errors="replace").splitlines(), 1):
        if declared.match(line):
            return f"{cmake}:{number}"
    return None


def executables(package: str) -> list[str]:
    from diffctl import demo_nodes

    names = [exe for pkg, exe in COMPONENTS if pkg == package] + demo_nodes.executables(package)
    lib = _lib_dir(package)
    if lib is not None:
        names += [p.name for p in lib.iterdir() if p.is_file() and os.access(p, os.X_OK)]
    return sorted(set(names))


def executable_argv(package: str, executable: str) -> list[str]:
    """The command line that starts `executable` of `package` (`<prefix>/lib/<package>/<executable>`, as
    launch_ros runs it, or a diffctl component)."""
    # The user's own package first; then diffctl's component of that name, even over an installed ROS
    # package (a sourced /opt/ros must not start the real robot_state_publisher); then install trees.
    program = _program(_lib_dir(package, workspace_only=True), executable) or _built_program(package, executable)
    if program is not None:
        return ros_programs.real_program_argv(program)
    from diffctl.workspace.gui_tools import argv_for

    gui = argv_for(package, executable)  # rqt_*, joint_state_publisher_gui …: a counterpart or a stand-in
    if gui is not None:
        return gui
    sub = COMPONENTS.get((package, executable))
    if sub is not None:
        return [sys.executable, "-m", "diffctl", *sub]
    program = _program(_lib_dir(package), executable)
    if program is not None:
        if not os.environ.get("RMW_IMPLEMENTATION") and not ros_programs.has_rmw_zenoh():
            raise LaunchError(
                f"{package}/{executable} is ROS 2's own ({program}): it joins diffctl's graph over rmw_zenoh, "
                f"which no install on AMENT_PREFIX_PATH has",
                hint=f"install {ros_programs.apt_name(ros_programs.RMW_ZENOH)} and source /opt/ros/jazzy/setup.bash "
                "again (or set RMW_IMPLEMENTATION to run it on another middleware, outside diffctl's graph)",
            )
        return ros_programs.real_program_argv(program)
    from diffctl import demo_nodes

    demo = demo_nodes.argv_for(package, executable)  # demo_nodes_cpp/py's talker…, where no real one is found
    if demo is not None:
        return demo
    if package not in known_packages():
        raise LaunchError(
            f"unknown package {package!r}{suggest(package, known_packages())}",
            hint=ros_programs.how_to_get(package),
        )
    compiled = _compiled_program(package, executable)
    if compiled is not None:
        raise LaunchError(
            f"{package}/{executable} is a compiled program of your workspace ({compiled}) that is not built",
            hint="build the workspace with colcon against a sourced ROS 2 (`colcon build`, then `source "
            "install/setup.bash`): diffctl then starts install/lib/" + f"{package}/{executable} in its graph",
        )
    available = executables(package)
    if not available:
        raise LaunchError(
            f"package {package!r} has no executables",
            hint="packages with executables: " + ", ".join(sorted(component_packages())),
        )
    raise LaunchError(
        f"package {package!r} has no executable {executable!r}{suggest(executable, available)}",
        hint="its executables: " + ", ".join(available),
    )


def launch_files(package_dir: Path) -> list[str]:
    d = package_dir / "launch"
    if not d.is_dir():
        return []
    return sorted(p.name for p in d.iterdir() if p.name.endswith(LAUNCH_SUFFIXES) or p.suffix == ".py")


def find_launch_file(target: str, file: str | None = None, cwd: Path | None = None) -> Path:
    """`NAME`, `PATH` or `PKG FILE` (as `ros2 launch` takes them) → the launch file to read."""
    if file is not None:
        share = share_dir(target)
        package = workspace.find_package(target)
        for candidate in (share / "launch" / file, share / file):
            if candidate.is_file():
                return candidate
        found = sorted(p for p in share.rglob(file) if p.is_file())
        if found:
            return found[0]
        origin = f"{package.origin} {package.source or package.prefix or share}"
        raise LaunchError(
            f"no launch file {file!r} in package {target!r} ({origin}){suggest(file, launch_files(share))}",
            hint="its launch files: " + (", ".join(launch_files(share)) or "none"),
        )
    path = Path(target)
    if path.is_file():
        return path.resolve()
    if path.is_dir():
        raise LaunchError(f"{target} is a directory, not a launch file")
    looks_like_path = "/" in target or target.endswith((".yaml", ".py", ".yml", ".xml", ".launch"))
    roots = [project_root()]
    here = (cwd or Path.cwd()).resolve()
    if here not in roots:
        roots.append(here)
    for root in roots:
        # NAME → launch/NAME.yaml, launch/NAME.launch.py; a bare file name → launch/FILE
        names = [target] if looks_like_path else [f"{target}{suffix}" for suffix in LAUNCH_SUFFIXES]
        for name in names if "/" not in target else []:
            candidate = root / "launch" / name
            if candidate.is_file():
                return candidate
    available = sorted({name.split(".")[0] for root in roots for name in launch_files(root)})
    if looks_like_path:
        raise LaunchError(f"launch file {target} does not exist")
    searched = ", ".join(str(root / "launch") for root in roots)
    raise LaunchError(
        f"no launch file named {target!r}{suggest(target, available)}",
        hint=f"searched {searched}; available: " + (", ".join(available) or "none") + "; or give a path or PKG FILE",
    )


PackageNotFoundError = workspace.PackageNotFoundError  # ament_index_python's, a KeyError too


def get_package_share_directory(package: str, print_warning: bool = True) -> str:
    """ament_index_python's function, for launch files written against it."""
    return str(share_dir(package))


def get_package_share_path(package: str, print_warning: bool = True) -> Path:
    """ament_index_python's pathlib variant."""
    return share_dir(package)


def get_package_prefix(package: str) -> str:
    """ament_index_python's function: `<prefix>/share/<package>` is the share directory."""
    return str(workspace.package_prefix(package))
