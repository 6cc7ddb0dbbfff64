"""The package index: `Node(package, executable)` → a command line, `$(find-pkg-share pkg)` → a directory.

diffctl's own components stand under the ROS names they replace and start as `python -m diffctl …`.
The project's packages are directories: `robot_description` is `description/`, `diff_sim` the top of the
project (so `$(find-pkg-share diff_sim)/launch`, `/config` work) — from a checkout, or from `diffctl/share`
in an installed wheel. Packages of an ament workspace on AMENT_PREFIX_PATH are found as ROS finds them.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

from diffctl.errors import LaunchError, suggest

# (package, executable) → diffctl subcommand
COMPONENTS: dict[tuple[str, str], tuple[str, ...]] = {
    ("robot_state_publisher", "robot_state_publisher"): ("robot-state-publisher",),
    ("controller_manager", "ros2_control_node"): ("control", "manager"),
    ("controller_manager", "spawner"): ("spawn", "controller"),
    ("ros_gz_sim", "gz_sim"): ("sim", "run"),
    ("ros_gz_sim", "create"): ("spawn", "entity"),
    ("ros_gz_bridge", "parameter_bridge"): ("bridge",),
    ("rviz2", "rviz2"): ("viz",),
    ("teleop_twist_joy", "teleop_node"): ("teleop", "joy"),
    ("teleop_twist_keyboard", "teleop_twist_keyboard"): ("teleop", "keyboard"),
    ("diffctl", "router"): ("router",),
}

LAUNCH_SUFFIXES = (".yaml", ".launch.yaml", ".launch.py", ".launch.xml", ".xml")


def project_root() -> Path:
    """The top of the project: the checkout holding diffctl/, or diffctl/share in an installed wheel."""
    override = os.environ.get("DIFFCTL_PROJECT_DIR")
    if override:
        return Path(override).resolve()
    package_dir = Path(__file__).resolve().parent.parent
    top = package_dir.parent
    if (top / "pyproject.toml").is_file() and (top / "launch").is_dir():
        return top
    return package_dir / "share"


# Share directories of component packages (launch files written for ROS include them, e.g. gz_sim.launch.py).
COMPONENT_SHARES = Path(__file__).resolve().parent / "share"


def project_packages() -> dict[str, Path]:
    root = project_root()
    packages = {"diff_sim": root, "robot_description": root / "description"}
    if COMPONENT_SHARES.is_dir():
        packages.update({p.name: p for p in COMPONENT_SHARES.iterdir() if p.is_dir()})
    return packages


def _ament_prefixes() -> list[Path]:
    return [Path(p) for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]


def component_packages() -> set[str]:
    return {pkg for pkg, _ in COMPONENTS}


def known_packages() -> list[str]:
    names = set(project_packages()) | component_packages()
    for prefix in _ament_prefixes():
        share = prefix / "share"
        if share.is_dir():
            names |= {p.name for p in share.iterdir() if p.is_dir()}
    return sorted(names)


def share_dir(package: str) -> Path:
    """The share directory of `package`, as ament_index's get_package_share_directory gives it."""
    project = project_packages()
    if package in project:
        return project[package]
    for prefix in _ament_prefixes():
        candidate = prefix / "share" / package
        if candidate.is_dir():
            return candidate
    if package in component_packages():
        raise LaunchError(
            f"package {package!r} is a diffctl component with no share directory",
            hint=f"start it with Node(package={package!r}, executable=…); share directories: "
            + ", ".join(sorted(project)),
        )
    raise LaunchError(
        f"unknown package {package!r}{suggest(package, known_packages())}",
        hint="known packages: " + ", ".join(known_packages()),
    )


def executables(package: str) -> list[str]:
    names = [exe for pkg, exe in COMPONENTS if pkg == package]
    for prefix in _ament_prefixes():
        lib = prefix / "lib" / package
        if lib.is_dir():
            names += [p.name for p in lib.iterdir() if p.is_file() and os.access(p, os.X_OK)]
    return sorted(set(names))


def executable_argv(package: str, executable: str) -> list[str]:
    """The command line that starts `executable` of `package`."""
    sub = COMPONENTS.get((package, executable))
    if sub is not None:
        return [sys.executable, "-m", "diffctl", *sub]
    for prefix in _ament_prefixes():
        candidate = prefix / "lib" / package / executable
        if candidate.is_file() and os.access(candidate, os.X_OK):
            return [str(candidate)]
    if package not in known_packages():
        raise LaunchError(
            f"unknown package {package!r}{suggest(package, known_packages())}",
            hint="packages with executables: " + ", ".join(sorted(component_packages())),
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
        for candidate in (share / "launch" / file, share / file):
            if candidate.is_file():
                return candidate
        found = sorted(p for p in share.rglob(file) if p.is_file())
        if found:
            return found[0]
        raise LaunchError(
            f"no launch file {file!r} in package {target!r}{suggest(file, launch_files(share))}",
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
    raise LaunchError(
        f"no launch file named {target!r}{suggest(target, available)}",
        hint="available: " + (", ".join(available) or "none") + "; or give a path or PKG FILE",
    )


def get_package_share_directory(package: str) -> str:
    """ament_index_python's function, for launch files written against it."""
    return str(share_dir(package))
