"""A Fuel URI → a local folder or file, in Gazebo's order: the cache, diffctl's known scenery, a download.

A model that cannot be had raises FuelModelUnavailable: one message naming the model, the cache folder
searched, why the download failed and the command that fetches it. `$DIFFCTL_FUEL_OFFLINE=1` skips downloads;
A world loads without the models it cannot have, each reported once (as Gazebo does, ARCHITECTURE.md "Gazebo
resources"); `$DIFFCTL_FUEL_SKIP_MISSING=0` makes such a model an error instead (the loader checks it).
"""

from __future__ import annotations

import os
import shlex
from pathlib import Path

from diffctl.errors import DescriptionError
from diffctl.fuel.cache import cache_root, cached_model, model_root
from diffctl.fuel.download import DownloadError, download_model
from diffctl.fuel.known import known_model
from diffctl.fuel.uri import FuelRef, parse_fuel_uri

OFFLINE_ENV = "DIFFCTL_FUEL_OFFLINE"
SKIP_MISSING_ENV = "DIFFCTL_FUEL_SKIP_MISSING"

_failed: dict[tuple[str, str, str, int | None], str] = {}  # one download attempt per model and process


class FuelModelUnavailable(DescriptionError):
    """A Fuel model that is neither cached, known to diffctl, nor downloadable now."""


def _flag(name: str) -> bool:
    return os.environ.get(name, "").strip().lower() in ("1", "true", "yes", "on")


def skip_missing() -> bool:
    """Whether a world loads without a Fuel model it cannot have (the default) or refuses to load (`=0`)."""
    return os.environ.get(SKIP_MISSING_ENV, "").strip().lower() not in ("0", "false", "no", "off")


def fetch_command(ref: FuelRef) -> str:
    return "diffctl fuel download " + shlex.quote(ref.original or ref.model_url)


def model_folder(ref: FuelRef) -> Path:
    """The local folder of the model `ref` names (downloading it if needed and allowed)."""
    found = cached_model(ref) or (known_model(ref) if ref.kind == "models" else None)
    if found is not None:
        return found
    key = (ref.host, ref.owner, ref.name, ref.version)
    reason = _failed.get(key)
    if reason is None:
        if _flag(OFFLINE_ENV):
            reason = f"downloads are off (${OFFLINE_ENV})"
        else:
            try:
                folder = download_model(ref)
            except DownloadError as e:
                reason = f"the download failed: {e}"
            else:
                if ref.version is None or folder.name == str(ref.version):
                    return folder
                reason = f"the server sent version {folder.name}, not {ref.version}"
        _failed[key] = reason
    version = "" if ref.version is None else f" version {ref.version}"
    what = "model" if ref.kind == "models" else "world"
    raise FuelModelUnavailable(
        f"Fuel {what} {ref.original or ref.model_url!r}{version} is not available: not in Gazebo's Fuel cache "
        f"(searched {model_root(ref)}/<version>/, cache {cache_root()} from $GZ_FUEL_CACHE_PATH or ~/.gz/fuel) "
        f"and {reason}",
        hint=f"fetch it with `{fetch_command(ref)}`",
    )


def resolve_fuel(uri: str) -> Path | None:
    """The folder (model URL) or file (model file URL) `uri` names; None when `uri` is not a Fuel URL.

    Raises FuelModelUnavailable when it is one but the model cannot be had, and DescriptionError for a file
    the model does not hold."""
    ref = parse_fuel_uri(uri)
    if ref is None or ref.kind != "models":
        return None
    folder = model_folder(ref)
    if ref.file is None:
        return folder
    path = folder / ref.file
    if not path.exists():
        raise DescriptionError(f"Fuel model {ref.model_url!r} has no file {ref.file!r} (looked in {folder})")
    return path


def resolve_fuel_world(uri: str) -> Path | None:
    """The world file a Fuel world URL names (`gz sim https://fuel…/worlds/X`), cached or downloaded; None
    when `uri` is not a Fuel world URL. Raises FuelModelUnavailable when it cannot be had."""
    from diffctl.fuel.cache import world_file

    ref = parse_fuel_uri(uri)
    if ref is None or ref.kind != "worlds" or ref.file is not None:
        return None
    return world_file(model_folder(ref))
