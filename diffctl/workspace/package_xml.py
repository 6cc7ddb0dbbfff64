"""A package's `package.xml` (REP 149): its name, build type and the exports diffctl reads.

Parsed with lxml, as catkin_pkg reads it: the name is `<name>` (not the directory), the build type is
`<export><build_type>`, defaulting to `catkin` when absent.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from diffctl.errors import ConfigError, xml_error

if TYPE_CHECKING:
    from lxml import etree

# ament_index_python's rule for a valid resource name.
NAME_RE = re.compile(r"^[a-zA-Z0-9][a-zA-Z0-9_-]+$")
# colcon-ros' run dependencies: build_export + buildtool_export + exec (and `depend`, which is all of them).
RUN_DEPEND_TAGS = ("depend", "build_export_depend", "buildtool_export_depend", "exec_depend", "run_depend")


@dataclass(frozen=True)
class PackageManifest:
    name: str
    build_type: str
    version: str = ""
    description: str = ""
    path: Path = Path()
    # <export><gazebo_ros gazebo_model_path="…" plugin_path="…"/>: attribute → value, as gz_sim.launch.py reads them
    gazebo_exports: dict[str, str] = field(default_factory=dict)
    # what colcon-ros records as run dependencies (share/colcon-core/packages/<name>): the order hooks apply in
    run_depends: tuple[str, ...] = ()


def _text(root: etree._Element, tag: str) -> str:
    el = root.find(tag)
    return (el.text or "").strip() if el is not None else ""


_cache: dict[Path, tuple[tuple[int, int], PackageManifest]] = {}


def read_manifest(path: Path) -> PackageManifest:
    """Read `path` (a package.xml); a broken file is one located ConfigError. Unchanged files are
    remembered (by modification time and size): every package lookup rescans the workspace."""
    try:
        st = path.stat()
    except OSError as e:
        raise ConfigError(f"cannot read package.xml: {e.strerror}", source=str(path)) from None
    key = (st.st_mtime_ns, st.st_size)
    hit = _cache.get(path)
    if hit is not None and hit[0] == key:
        return hit[1]
    manifest = _parse_manifest(path)
    _cache[path] = (key, manifest)
    return manifest


def _parse_manifest(path: Path) -> PackageManifest:
    from lxml import etree  # ~8 MB resident: only for a workspace that has packages to read

    try:
        root = etree.parse(str(path), etree.XMLParser(resolve_entities=False, no_network=True)).getroot()
    except etree.XMLSyntaxError as e:
        raise xml_error(e, str(path), "malformed package.xml", ConfigError) from None
    except OSError as e:
        raise ConfigError(f"cannot read package.xml: {e}", source=str(path)) from None
    if root.tag != "package":
        raise ConfigError(f"root element is <{root.tag}>, not <package>", source=str(path), line=root.sourceline)
    name = _text(root, "name")
    if not name:
        raise ConfigError("package.xml has no <name>", source=str(path), line=root.sourceline, field="name")
    if not NAME_RE.match(name):
        el = root.find("name")
        raise ConfigError(
            f"package name {name!r} is not valid",
            source=str(path),
            line=el.sourceline if el is not None else None,
            field="name",
            hint="letters, digits, '_' and '-', starting with a letter or digit",
        )
    build_type = "catkin"
    gazebo: dict[str, str] = {}
    export = root.find("export")
    if export is not None:
        bt = export.find("build_type")
        if bt is not None and (bt.text or "").strip():
            build_type = (bt.text or "").strip()
        gz = export.find("gazebo_ros")
        if gz is not None:
            gazebo = {k: v for k, v in gz.attrib.items() if isinstance(k, str)}
    run_depends = tuple(
        dict.fromkeys(
            (el.text or "").strip() for tag in RUN_DEPEND_TAGS for el in root.findall(tag) if (el.text or "").strip()
        )
    )
    return PackageManifest(
        name=name,
        run_depends=run_depends,
        build_type=build_type,
        version=_text(root, "version"),
        description=" ".join(_text(root, "description").split()),
        path=path,
        gazebo_exports=gazebo,
    )
