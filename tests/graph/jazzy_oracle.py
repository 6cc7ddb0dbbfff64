"""The ROS 2 Jazzy interface oracle: rosidl's type description JSON files from the Jazzy wheels on PyPI.

The `ros-<pkg>` wheels carry `share/<pkg>/{msg,srv}/<Type>.json` exactly as rosidl generated them for the
release, with the RIHS01 hash of the type and of every type it references. They are downloaded once with pip
(`--no-deps`, nothing installed) into a cache directory and read straight from the wheel zips.
"""

from __future__ import annotations

import contextlib
import fcntl
import json
import os
import subprocess
import sys
import zipfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

# Jazzy releases: common_interfaces 5.3.x, rcl_interfaces 2.0.x (builtin_interfaces … type_description_interfaces).
JAZZY_WHEELS = {
    "ros-std-msgs": "5.3.6", "ros-geometry-msgs": "5.3.6", "ros-sensor-msgs": "5.3.6", "ros-nav-msgs": "5.3.6",
    "ros-std-srvs": "5.3.6", "ros-visualization-msgs": "5.3.6", "ros-builtin-interfaces": "2.0.3",
    "ros-rcl-interfaces": "2.0.3", "ros-rosgraph-msgs": "2.0.3", "ros-lifecycle-msgs": "2.0.3",
    "ros-service-msgs": "2.0.3", "ros-type-description-interfaces": "2.0.3", "ros-action-msgs": "2.0.3",
    "ros-shape-msgs": "5.3.6", "ros-trajectory-msgs": "5.3.6", "ros-actionlib-msgs": "5.3.6",
    "ros-diagnostic-msgs": "5.3.6", "ros-stereo-msgs": "5.3.6", "ros-unique-identifier-msgs": "2.5.0",
    "ros-rmw-dds-common": "3.1.0",
}


def cache_dir() -> Path:
    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    return base / "diffctl" / "jazzy-oracle"


@contextlib.contextmanager
def filling(d: Path) -> Iterator[None]:
    """One process at a time fills the cache folder `d` (pytest-xdist's workers share it: a wheel pip is still
    writing must not be read half done by the other)."""
    d.mkdir(parents=True, exist_ok=True)
    with open(d / ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        yield


def fetch() -> list[Path]:
    """The Jazzy wheels, downloaded once (pip, no dependencies, nothing installed)."""
    d = cache_dir()
    with filling(d):
        missing = [f"{p}=={v}" for p, v in JAZZY_WHEELS.items() if not _find(d, p, v)]
        if missing:
            subprocess.run(
                [sys.executable, "-m", "pip", "download", "--no-deps", "--only-binary=:all:", "-q", "-d", str(d),
                 *missing],
                check=True, timeout=600,
            )
    return [w for p, v in JAZZY_WHEELS.items() if (w := _find(d, p, v)) is not None]


def _find(d: Path, package: str, version: str) -> Path | None:
    stem = package.replace("-", "_")
    hits = sorted(d.glob(f"{stem}-{version}-*.whl"))
    return hits[0] if hits else None


def descriptions(wheels: list[Path]) -> dict[str, dict[str, Any]]:
    """type name (pkg/msg/T or pkg/srv/T) → rosidl's JSON for it."""
    out: dict[str, dict[str, Any]] = {}
    for wheel in wheels:
        with zipfile.ZipFile(wheel) as z:
            for name in z.namelist():
                parts = name.split("/")
                # <dist>.data/data/share/<pkg>/<msg|srv>/<Type>.json
                if len(parts) >= 4 and parts[-4] == "share" and parts[-2] in ("msg", "srv") \
                        and name.endswith(".json"):
                    data = json.loads(z.read(name))
                    out[data["type_description_msg"]["type_description"]["type_name"]] = data
    return out


def hashes(descs: dict[str, dict[str, Any]]) -> dict[str, str]:
    """Every type hash the JSON files state, referenced types included."""
    out: dict[str, str] = {}
    for data in descs.values():
        for h in data["type_hashes"]:
            out[h["type_name"]] = h["hash_string"]
    return out
