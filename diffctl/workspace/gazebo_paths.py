"""Gazebo search paths from package exports, as ros_gz_sim's gz_sim.launch.py collects them.

A package.xml `<export><gazebo_ros gazebo_model_path="…" plugin_path="…"/>` adds to GZ_SIM_RESOURCE_PATH
and GZ_SIM_SYSTEM_PLUGIN_PATH; `${prefix}` in the value stands for the package's share directory, so the
common `${prefix}/..` makes `model://<pkg>/…` resolve. Workspace packages count with their share tree.
"""

from __future__ import annotations

from pathlib import Path

from diffctl.errors import ConfigError
from diffctl.workspace.package_xml import read_manifest
from diffctl.workspace.resolve import ORIGIN_WORKSPACE, find_package, list_packages


def _exports(manifest_path: Path) -> dict[str, str]:
    try:
        return read_manifest(manifest_path).gazebo_exports
    except ConfigError:
        return {}  # an unreadable installed manifest has nothing to export; resolving it reports the error


def gazebo_paths() -> tuple[list[str], list[str]]:
    """(resource paths, system plugin paths) exported by every package found, in precedence order."""
    models: list[str] = []
    plugins: list[str] = []
    for pkg in list_packages():
        manifest = (pkg.source or pkg.share) / "package.xml"
        if not manifest.is_file():
            continue
        exports = _exports(manifest)
        if not exports:
            continue
        share = find_package(pkg.name).share if pkg.origin == ORIGIN_WORKSPACE else pkg.share
        for attr, out in (("gazebo_model_path", models), ("plugin_path", plugins)):
            value = exports.get(attr)
            if value:
                path = str(Path(value.replace("${prefix}", str(share))).resolve())
                if path not in out:
                    out.append(path)
    return models, plugins
