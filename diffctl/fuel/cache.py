"""Gazebo's Fuel cache on disk, laid out as gz-fuel-tools writes it (LocalCache::SaveModel, uriToPath).

`<cache>/<host>/<owner>/models/<name>/<N>/model.config`, worlds `…/worlds/<name>/<N>/<file>.sdf`: the host with
`:` → `%3A` and `@` → `%40`, owner and name lowercased, `<N>` an integer ≥ 1 (there is never a `tip` folder),
and a version folder counts only when it holds its model.config (a world: its world file). The cache is
`$GZ_FUEL_CACHE_PATH` (or the deprecated `$IGN_FUEL_CACHE_PATH`), else `~/.gz/fuel`. "tip" means the highest
version already on disk.
"""

from __future__ import annotations

import os
from pathlib import Path

from diffctl.fuel.uri import FuelRef

CACHE_ENV = ("GZ_FUEL_CACHE_PATH", "IGN_FUEL_CACHE_PATH")


def cache_root() -> Path:
    """`$GZ_FUEL_CACHE_PATH`, else `cache: path:` of `~/.gz/fuel/config.yaml` (gz-fuel-tools' ClientConfig), else
    `~/.gz/fuel`."""
    for var in CACHE_ENV:
        value = os.environ.get(var, "").strip()
        if value:
            return Path(value).expanduser()
    default = Path.home() / ".gz" / "fuel"
    configured = _config_cache_path(default / "config.yaml")
    return configured or default


def _config_cache_path(config: Path) -> Path | None:
    try:
        text = config.read_text()
    except OSError:
        return None
    import yaml

    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError:
        return None  # Gazebo reports a broken config.yaml itself; the default cache still works
    cache = data.get("cache") if isinstance(data, dict) else None
    path = cache.get("path") if isinstance(cache, dict) else None
    return Path(str(path)).expanduser() if path else None


def host_folder(host: str) -> str:
    return host.replace(":", "%3A").replace("@", "%40")


def model_root(ref: FuelRef, root: Path | None = None) -> Path:
    """The folder holding the version folders of `ref` (it may not exist)."""
    return (root or cache_root()) / host_folder(ref.host) / ref.owner / ref.kind / ref.name


def _child_ci(parent: Path, name: str) -> Path | None:
    """`parent/name`, or a sibling spelled with other letter case (gz-fuel-tools lowercases names it reads back)."""
    exact = parent / name
    if exact.is_dir():
        return exact
    if not parent.is_dir():
        return None
    wanted = name.lower()
    return next((p for p in sorted(parent.iterdir()) if p.name.lower() == wanted and p.is_dir()), None)


def is_complete(folder: Path, kind: str) -> bool:
    """A model version counts with its model.config; a world version with its world file."""
    if kind == "models":
        return (folder / "model.config").is_file()
    return world_file(folder) is not None


def world_file(folder: Path) -> Path | None:
    """The .sdf (or .world) file of a cached Fuel world version."""
    found = sorted(p for p in folder.iterdir() if p.suffix in (".sdf", ".world") and p.is_file())
    return found[0] if found else None


def cached_versions(ref: FuelRef, root: Path | None = None) -> dict[int, Path]:
    """Version → folder of every valid cached copy of `ref`."""
    top = root or cache_root()
    folder: Path | None = top / host_folder(ref.host)
    for part in (ref.owner, ref.kind, ref.name):
        folder = _child_ci(folder, part) if folder is not None else None
    if folder is None:
        return {}
    out: dict[int, Path] = {}
    for d in folder.iterdir():
        if d.name.isdigit() and int(d.name) >= 1 and is_complete(d, ref.kind):
            out[int(d.name)] = d
    return out


def cached_model(ref: FuelRef, root: Path | None = None) -> Path | None:
    """The cached model folder `ref` names: its exact version, or the highest one for tip."""
    versions = cached_versions(ref, root)
    if not versions:
        return None
    if ref.version is None:
        return versions[max(versions)]
    return versions.get(ref.version)
