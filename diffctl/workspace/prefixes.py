"""Installed packages on AMENT_PREFIX_PATH and COLCON_PREFIX_PATH, as ament_index_python finds them.

A package `pkg` is in prefix P when `P/share/ament_index/resource_index/packages/pkg` exists; the first
prefix holding it wins. COLCON_PREFIX_PATH lists install bases (`ws/install`), each an isolated layout
(one prefix per package) or a merged one (`.colcon_install_layout`). A stale symlink install (its
package.xml link points nowhere, e.g. after the sources moved) is skipped, never used.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

MARKERS = Path("share/ament_index/resource_index/packages")


@dataclass(frozen=True)
class InstallPrefix:
    path: Path
    origin: str  # the variable that named it


def _split(variable: str) -> list[Path]:
    return [Path(p) for p in os.environ.get(variable, "").split(os.pathsep) if p and os.path.isdir(p)]


def install_prefixes() -> list[InstallPrefix]:
    out: list[InstallPrefix] = [InstallPrefix(p, "AMENT_PREFIX_PATH") for p in _split("AMENT_PREFIX_PATH")]
    for base in _split("COLCON_PREFIX_PATH"):
        layout = base / ".colcon_install_layout"
        merged = layout.is_file() and layout.read_text(errors="replace").strip() == "merged"
        if merged or (base / MARKERS).is_dir():
            out.append(InstallPrefix(base, "COLCON_PREFIX_PATH"))
        else:
            out.extend(
                InstallPrefix(sub, "COLCON_PREFIX_PATH")
                for sub in sorted(base.iterdir())
                if sub.is_dir() and (sub / MARKERS).is_dir()
            )
    seen: set[Path] = set()
    unique = []
    for p in out:
        if p.path.resolve() not in seen:
            seen.add(p.path.resolve())
            unique.append(p)
    return unique


def stale_reason(prefix: Path, package: str) -> str | None:
    """Why `prefix`'s copy of `package` cannot be used, or None when it can."""
    share = prefix / "share" / package
    if not share.is_dir():
        return f"{share} is missing"
    manifest = share / "package.xml"
    if manifest.is_symlink() and not manifest.exists():
        return f"{manifest} points to {os.readlink(manifest)}, which no longer exists"
    return None


def packages_in(prefix: Path) -> list[str]:
    markers = prefix / MARKERS
    if not markers.is_dir():
        return []
    return sorted(p.name for p in markers.iterdir() if not p.name.startswith("."))
