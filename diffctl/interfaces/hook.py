"""The meta-path hook that makes interface packages importable: installed at interpreter start, cheap.

`diffctl-interfaces.pth` (in the venv's site-packages, from the editable install or the wheel) imports a copy
of this module installed beside it as `diffctl_interfaces_hook`; `diffctl.interfaces` imports it too
(one finder either way). It imports nothing of diffctl until a name may be an interface package.
It appends one finder to `sys.meta_path`, AFTER the normal path
finder, so modules on sys.path (a sourced ROS 2's message packages) always win. The finder answers only
`<pkg>`, `<pkg>.msg|srv|action` and `<pkg>.<kind>._<module>`; for a top-level name it first checks, with
the standard library only, whether the name can be an interface package (one of diffctl's, a folder of the
workspace's src/, an install tree's share/<pkg>/msg|srv|action, or named like one), so other failed
imports cost next to nothing; only then is `finder.py` (the registry, the workspace reader) imported.
PYTEST_DONT_REWRITE: pytest marks the modules of a distribution with a pytest11 plugin for assertion
rewriting; this one is imported before pytest starts, and says so to keep pytest from warning about it.
"""

from __future__ import annotations

import os
import sys

# diffctl's own interface packages (the bus's typestore and the shipped Jazzy texts; a test keeps this in
# step with the registry): checked without importing the registry.
KNOWN = frozenset({
    "ackermann_msgs", "action_msgs", "actionlib_msgs", "actuator_msgs", "builtin_interfaces",
    "composition_interfaces", "control_msgs", "controller_manager_msgs", "diagnostic_msgs", "example_interfaces",
    "geographic_msgs", "geometry_msgs", "gps_msgs", "lifecycle_msgs", "nav_msgs", "rcl_interfaces",
    "rmw_dds_common", "robot_localization", "ros_gz_interfaces", "rosbag2_interfaces", "rosgraph_msgs",
    "sensor_msgs", "service_msgs", "shape_msgs", "statistics_msgs", "std_msgs", "std_srvs", "stereo_msgs",
    "tf2_msgs", "topic_tools_interfaces",
    "trajectory_msgs", "type_description_interfaces", "unique_identifier_msgs", "vision_msgs", "visualization_msgs",
})
_SUFFIXES = ("_msgs", "_srvs", "_interfaces", "_actions", "_msg", "_srv", "_action")
_KINDS = ("msg", "srv", "action")
_workspace_dirs: dict[str, frozenset[str]] = {}



def _packages_under(root: str) -> frozenset[str]:
    """Folder and manifest names of the packages in `root`/src, walked once per process (and not far: a
    `src` that is no workspace, say ~/src full of other repositories, costs a bounded walk)."""
    dirs = _workspace_dirs.get(root)
    if dirs is None:
        found = set()
        for visited, (dirpath, dirnames, filenames) in enumerate(
                os.walk(os.path.join(root, "src"), followlinks=True)):
            if visited > 20000:
                break
            if "package.xml" in filenames:
                found.add(os.path.basename(dirpath))
                try:
                    with open(os.path.join(dirpath, "package.xml"), encoding="utf-8", errors="replace") as f:
                        text = f.read()
                except OSError:
                    text = ""
                start = text.find("<name>") + len("<name>")
                end = text.find("</name>", start)
                if start >= len("<name>") and end > start:
                    found.add(text[start:end].strip())
                dirnames[:] = []
            else:
                dirnames[:] = [d for d in dirnames if not d.startswith(".")]
        dirs = _workspace_dirs[root] = frozenset(found)
    return dirs


def _workspace_packages() -> frozenset[str]:
    """The packages of $DIFFCTL_WORKSPACE, else of the nearest folder above the current one whose src/ holds
    packages (a package's own C++ src/ is passed over), as diffctl.workspace finds the workspace."""
    env = os.environ.get("DIFFCTL_WORKSPACE")
    if env:
        return _packages_under(env)
    try:
        here = os.getcwd()
    except OSError:
        return frozenset()
    while True:
        if os.path.isdir(os.path.join(here, "src")):
            found = _packages_under(here)
            if found:
                return found
        parent = os.path.dirname(here)
        if parent == here:
            return frozenset()
        here = parent


def in_workspace(name: str) -> bool:
    return name in _workspace_packages()


def in_install_trees(name: str) -> bool:
    for var in ("AMENT_PREFIX_PATH", "COLCON_PREFIX_PATH"):
        for prefix in os.environ.get(var, "").split(os.pathsep):
            if prefix and any(os.path.isdir(os.path.join(prefix, "share", name, k)) for k in _KINDS):
                return True
            if var == "COLCON_PREFIX_PATH" and prefix and os.path.isdir(os.path.join(prefix, name, "share")):
                return True
    return False


def may_be_interface_package(name: str) -> bool:
    if name in KNOWN or name.endswith(_SUFFIXES):
        return True
    if name in sys.stdlib_module_names or name.startswith("_"):
        return False
    return in_install_trees(name) or in_workspace(name)


class InterfaceFinder:
    """Finds `<pkg>[.msg|.srv|.action[._module]]` of interface packages nothing earlier on sys.path has."""

    def find_spec(self, fullname: str, path: object = None, target: object = None) -> object:
        top, _, rest = fullname.partition(".")
        if rest:
            parts = rest.split(".")
            if parts[0] not in _KINDS or len(parts) > 2:
                return None
        elif not may_be_interface_package(top):
            return None
        from diffctl.interfaces import finder

        try:
            return finder.find_spec(fullname)
        except ImportError as e:
            # A malformed .msg or a missing package is one located message (file:line: what is wrong): the
            # traceback through the registry and the parser would only bury it, so it starts here.
            raise e.with_traceback(None) from None

    def invalidate_caches(self) -> None:
        _workspace_dirs.clear()


def install() -> None:
    if not any(type(f).__name__ == "InterfaceFinder" for f in sys.meta_path):
        sys.meta_path.append(InterfaceFinder())


install()
