"""Finding the user's workspace and the packages in its `src/`, the way colcon's crawl finds them.

A workspace is a folder whose `src/` holds ROS packages (`package.xml` files whose root is `<package>`, as
colcon-ros identifies them). The crawl follows symlinks, skips directories whose name starts with `.`, skips
subtrees holding `COLCON_IGNORE`, `AMENT_IGNORE` or `CATKIN_IGNORE`, and stops descending at a package (nested
packages are not packages). Looking upward from the working directory, a folder counts only when the working
directory is that folder or lies in its `src/`, or when colcon has built there (its `build/`, `install/` or
`log/` holds the COLCON_IGNORE colcon writes): an unrelated `src/` higher up (say `~/src` full of other
repositories) is never taken for the user's workspace.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from functools import lru_cache
from pathlib import Path

from diffctl.errors import ConfigError

WORKSPACE_ENV = "DIFFCTL_WORKSPACE"
IGNORE_MARKERS = ("COLCON_IGNORE", "AMENT_IGNORE", "CATKIN_IGNORE")
COLCON_OUTPUTS = ("build", "install", "log")


def crawl(base: Path) -> Iterator[Path]:
    """Package directories under `base` (each holds a package.xml), in a stable order."""
    seen: set[str] = set()
    for dirpath, dirnames, filenames in os.walk(base, followlinks=True):
        real = os.path.realpath(dirpath)
        names = set(filenames) | set(dirnames)
        # A symlink loop would walk forever; an ignored subtree is not entered.
        if real in seen or any(m in names for m in IGNORE_MARKERS):
            dirnames[:] = []
            continue
        seen.add(real)
        if "package.xml" in filenames:
            dirnames[:] = []
            yield Path(dirpath)
            continue
        dirnames[:] = sorted(d for d in dirnames if not d.startswith("."))


def _is_ros_package(directory: Path) -> bool:
    from diffctl.workspace.package_xml import read_manifest

    try:
        read_manifest(directory / "package.xml")
    except ConfigError:
        return False
    return True


def holds_packages(src: Path) -> bool:
    return src.is_dir() and any(_is_ros_package(p) for p in crawl(src))


def built_by_colcon(directory: Path) -> bool:
    """Whether colcon has built in `directory` (it leaves COLCON_IGNORE in its build/, install/ and log/)."""
    return any((directory / out / "COLCON_IGNORE").is_file() for out in COLCON_OUTPUTS)


def _named_workspace(directory: Path, origin: str) -> Path:
    d = directory.expanduser().resolve()
    if not d.is_dir():
        raise ConfigError(f"{origin}: {directory} is not a directory", hint="name a workspace folder holding src/")
    if holds_packages(d / "src"):
        return d
    if d.name == "src" and holds_packages(d):
        return d.parent
    raise ConfigError(
        f"{origin}: {directory} is not a workspace (no src/ folder holding package.xml files)",
        hint="name the folder that holds src/",
    )


def find_workspace(explicit: str | Path | None = None, start: str | Path | None = None) -> Path | None:
    """The user's workspace root: `explicit` (--workspace), else $DIFFCTL_WORKSPACE, else the enclosing
    workspace of `start` (default: the current directory), else None."""
    if explicit is not None and str(explicit):
        return _named_workspace(Path(explicit), "--workspace")
    env = os.environ.get(WORKSPACE_ENV, "")
    if env:
        return _named_workspace(Path(env), WORKSPACE_ENV)
    return _enclosing(str(Path(start if start is not None else os.getcwd()).resolve()))


@lru_cache(maxsize=64)
def _enclosing(start: str) -> Path | None:
    # Remembered per process: a `src/` that is no workspace (say ~/src full of other repositories) is
    # crawled once, not on every package lookup.
    here = Path(start)
    for d in (here, *here.parents):
        if (d == here or here.is_relative_to(d / "src") or built_by_colcon(d)) and holds_packages(d / "src"):
            return d
    return None
