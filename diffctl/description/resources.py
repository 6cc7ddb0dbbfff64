"""Where SDF URIs point on disk: `model://`, `package://`, `file://`, absolute and relative paths.

The search path is what Gazebo users set (GZ_SIM_RESOURCE_PATH, and the older IGN_GAZEBO_RESOURCE_PATH and
SDF_PATH), plus the directory of the including file and its parent, so a sibling model folder resolves as
`model://name` without configuration.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from pathlib import Path

from lxml import etree

RESOURCE_PATH_VARIABLES = ("GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH", "SDF_PATH")


def env_search_path() -> list[Path]:
    out: list[Path] = []
    for var in RESOURCE_PATH_VARIABLES:
        for part in os.environ.get(var, "").split(os.pathsep):
            if part:
                out.append(Path(part))
    return out


def search_path_for(base_dir: Path, extra: Iterable[str | Path] = ()) -> tuple[Path, ...]:
    """Directories to look in, in order: explicit ones, the environment, the file's directory and its parent."""
    dirs = [Path(p) for p in extra] + env_search_path() + [base_dir, base_dir.parent]
    seen: set[Path] = set()
    out: list[Path] = []
    for d in dirs:
        d = d.expanduser().resolve()
        if d not in seen:
            seen.add(d)
            out.append(d)
    return tuple(out)


def is_remote(uri: str) -> bool:
    return uri.startswith(("http://", "https://"))


def resolve_uri(uri: str, base_dir: Path, search_path: Iterable[Path]) -> Path | None:
    """The existing file or directory `uri` names, or None."""
    uri = uri.strip()
    if is_remote(uri):
        return None
    for scheme in ("model://", "package://"):
        if uri.startswith(scheme):
            rest = uri[len(scheme) :]
            for d in search_path:
                candidate = d / rest
                if candidate.exists():
                    return candidate.resolve()
            return None
    if uri.startswith("file://"):
        uri = uri[len("file://") :]
    path = Path(uri).expanduser()
    if path.is_absolute():
        return path.resolve() if path.exists() else None
    for d in (base_dir, *search_path):
        candidate = d / path
        if candidate.exists():
            return candidate.resolve()
    return None


def model_file_in(directory: Path) -> Path | None:
    """The SDF file of a Gazebo model folder: model.config's <sdf> (highest version) or model.sdf."""
    config = directory / "model.config"
    if config.is_file():
        try:
            root = etree.parse(str(config)).getroot()
        except etree.XMLSyntaxError:
            root = None
        if root is not None:
            entries = []
            for sdf in root.iter("sdf"):
                name = (sdf.text or "").strip()
                if name:
                    version = tuple(int(p) for p in (sdf.get("version") or "0").split(".") if p.isdigit())
                    entries.append((version, name))
            for _, name in sorted(entries, reverse=True):
                candidate = directory / name
                if candidate.is_file():
                    return candidate
    candidate = directory / "model.sdf"
    return candidate if candidate.is_file() else None
