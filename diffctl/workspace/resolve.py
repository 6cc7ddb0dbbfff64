"""Package resolution in ROS order: the user's workspace (sources), install trees, then diffctl's own.

A workspace package resolves to a prefix in diffctl's cache, synced from its install rules on every
lookup (share_tree.py); an install tree's package resolves to its own prefix; a diffctl package to its
folder. The first place holding the name wins, so a user's package always shadows a diffctl one.
One exception keeps a shell with /opt/ros sourced working: the ROS packages diffctl replaces
(ros_gz_sim, …) come before install trees, whose copies would start the real Gazebo.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from diffctl.errors import ConfigError, LaunchError, suggest
from diffctl.workspace import builtin, prefixes
from diffctl.workspace.discovery import WORKSPACE_ENV, crawl, find_workspace
from diffctl.workspace.install_rules import InstallIndex, cmake_install_index
from diffctl.workspace.package_xml import NAME_RE, PackageManifest, read_manifest
from diffctl.workspace.ros_programs import how_to_get
from diffctl.workspace.setup_py import python_install_index
from diffctl.workspace.share_tree import materialize, workspace_cache

ORIGIN_WORKSPACE = "workspace"
ORIGIN_DIFFCTL = "diffctl"


class PackageNotFoundError(LaunchError, KeyError):
    """A package no search place holds (a KeyError too, like ament_index_python's)."""


@dataclass(frozen=True)
class Package:
    name: str
    origin: str  # "workspace", "AMENT_PREFIX_PATH", "COLCON_PREFIX_PATH" or "diffctl"
    share: Path
    prefix: Path | None = None  # None for diffctl's packages, which are plain folders
    source: Path | None = None  # the package folder in the workspace's src/
    build_type: str = ""
    problems: tuple[str, ...] = ()


@dataclass
class WorkspaceScan:
    root: Path
    manifests: dict[str, PackageManifest] = field(default_factory=dict)
    duplicates: dict[str, list[Path]] = field(default_factory=dict)
    broken: list[str] = field(default_factory=list)  # package.xml files that could not be read


def scan_workspace(root: Path) -> WorkspaceScan:
    scan = WorkspaceScan(root)
    for pkg_dir in crawl(root / "src"):
        try:
            manifest = read_manifest(pkg_dir / "package.xml")
        except ConfigError as e:
            scan.broken.append(str(e))
            continue
        if manifest.name in scan.manifests:
            scan.duplicates.setdefault(manifest.name, [scan.manifests[manifest.name].path]).append(manifest.path)
            continue
        scan.manifests[manifest.name] = manifest
    return scan


def install_index(manifest: PackageManifest) -> InstallIndex:
    pkg_dir = manifest.path.parent
    if manifest.build_type == "ament_python" or (
        not (pkg_dir / "CMakeLists.txt").is_file() and (pkg_dir / "setup.py").is_file()
    ):
        return python_install_index(pkg_dir, manifest.name)
    index = cmake_install_index(pkg_dir, manifest.name)
    share_xml = f"share/{manifest.name}/package.xml"
    if share_xml not in index.files:
        # ament_package() installs it; a package that never calls it still has its manifest found.
        index.add(share_xml, manifest.path)
    return index


def _workspace_package(scan: WorkspaceScan, name: str) -> Package:
    if name in scan.duplicates:
        paths = " and ".join(str(p) for p in scan.duplicates[name])
        raise ConfigError(f"package {name!r} is defined twice in workspace {scan.root}: {paths}")
    manifest = scan.manifests[name]
    index = install_index(manifest)
    prefix = materialize(
        workspace_cache(scan.root) / name, name, manifest.path.parent, index, python_sources(scan, name)
    )
    return Package(
        name,
        ORIGIN_WORKSPACE,
        prefix / "share" / name,
        prefix,
        manifest.path.parent,
        manifest.build_type,
        tuple(index.problems),
    )


def python_sources(scan: WorkspaceScan, first: str) -> list[Path]:
    """The source folders of the workspace's Python packages, `first`'s own ahead: what its programs
    import from (colcon would have installed each into site-packages). A folder counts when it holds
    `<name>/__init__.py` (ament_python, ament_cmake_python) or a setup.py; `first`'s always does."""
    found: list[Path] = []
    for name in [first, *sorted(n for n in scan.manifests if n != first)]:
        manifest = scan.manifests.get(name)
        if manifest is None:
            continue
        folder = manifest.path.parent
        if name == first or (folder / name / "__init__.py").is_file() or (folder / "setup.py").is_file():
            found.append(folder.resolve())
    return found


def workspace_python_path(workspace: Path) -> list[Path]:
    """The source folders of every Python package of `workspace`: what a built and sourced workspace makes
    importable (ament_python's packages, ament_cmake's `ament_python_install_package`, as nav2_common's
    RewrittenYaml), for launch files and for every process."""
    return python_sources(scan_workspace(workspace), "")


def find_package(name: str, workspace: Path | None = None) -> Package:
    """The package `name` from the first place that holds it; PackageNotFoundError (exit 2) otherwise.
    `workspace` None means the one find_workspace() finds (--workspace, $DIFFCTL_WORKSPACE, enclosing)."""
    if not NAME_RE.match(name):
        raise ConfigError(
            f"{name!r} is not a valid package name",
            hint="letters, digits, '_' and '-', starting with a letter or digit",
        )
    ws = workspace or find_workspace()
    scan = scan_workspace(ws) if ws is not None else None
    if scan is not None and (name in scan.manifests or name in scan.duplicates):
        return _workspace_package(scan, name)
    replaced = builtin.replacement_packages()
    if name in replaced:
        return Package(name, ORIGIN_DIFFCTL, replaced[name])
    stale: list[str] = []
    for p in prefixes.install_prefixes():
        if (p.path / prefixes.MARKERS / name).is_file():
            reason = prefixes.stale_reason(p.path, name)
            if reason is None:
                return Package(name, p.origin, p.path / "share" / name, p.path)
            stale.append(f"{p.origin} {p.path}: {reason}")
    library = builtin.LIBRARY_PREFIX
    if (library / prefixes.MARKERS / name).is_file():
        return Package(name, ORIGIN_DIFFCTL, library / "share" / name, library)
    demo = builtin.demo_packages()
    if name in demo:
        return Package(name, ORIGIN_DIFFCTL, demo[name])
    raise _not_found(name, scan, stale)


def _not_found(name: str, scan: WorkspaceScan | None, stale: list[str]) -> PackageNotFoundError:
    known = [p.name for p in list_packages(scan.root if scan else None, scan=scan)]
    searched = []
    if scan is not None:
        searched.append(f"workspace {scan.root} ({len(scan.manifests)} packages)")
    else:
        searched.append(f"no workspace (none encloses the current directory; use --workspace or {WORKSPACE_ENV})")
    searched.extend(f"{p.origin} {p.path}" for p in prefixes.install_prefixes())
    searched.append("diffctl's packages")
    extra = "".join(f"; skipped stale install {s}" for s in stale)
    if scan is not None and scan.broken:
        extra += "; unreadable: " + "; ".join(scan.broken)
    return PackageNotFoundError(
        f"package {name!r} not found{suggest(name, known)}",
        hint=how_to_get(name) + "; searched: " + ", ".join(searched) + extra,
    )


def list_packages(workspace: Path | None = None, *, scan: WorkspaceScan | None = None) -> list[Package]:
    """Every package found, the winner of each name only, in precedence order then by name."""
    ws = workspace or find_workspace()
    if scan is None and ws is not None:
        scan = scan_workspace(ws)
    found: dict[str, Package] = {}
    if scan is not None:
        for name, m in sorted(scan.manifests.items()):
            prefix = workspace_cache(scan.root) / name
            found[name] = Package(name, ORIGIN_WORKSPACE, prefix / "share" / name, prefix, m.path.parent, m.build_type)
    for name, share in builtin.replacement_packages().items():
        found.setdefault(name, Package(name, ORIGIN_DIFFCTL, share))
    for p in prefixes.install_prefixes():
        for name in prefixes.packages_in(p.path):
            if name not in found and prefixes.stale_reason(p.path, name) is None:
                found[name] = Package(name, p.origin, p.path / "share" / name, p.path)
    for name in prefixes.packages_in(builtin.LIBRARY_PREFIX):
        library = builtin.LIBRARY_PREFIX
        found.setdefault(name, Package(name, ORIGIN_DIFFCTL, library / "share" / name, library))
    for name, share in builtin.demo_packages().items():
        found.setdefault(name, Package(name, ORIGIN_DIFFCTL, share))
    return list(found.values())
