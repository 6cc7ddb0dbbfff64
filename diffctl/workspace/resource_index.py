"""ament's resource index on AMENT_PREFIX_PATH: resource types, resources and their contents (ament_index_python's
get_resource* functions, with its errors and messages).

Each prefix on AMENT_PREFIX_PATH may hold `share/ament_index/resource_index/<type>/<name>` files; a name found in
an earlier prefix hides the same name in a later one. Types are folders and names files, so a name holding a
path separator is refused rather than resolved somewhere else on disk.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Literal

RESOURCE_INDEX_SUBFOLDER = "share/ament_index/resource_index"
AMENT_PREFIX_PATH_ENV_VAR = "AMENT_PREFIX_PATH"


class InvalidResourceTypeNameError(ValueError):
    """A resource type holding a path separator."""


class InvalidResourceNameError(ValueError):
    """A resource name holding a path separator."""


def get_search_paths() -> list[str]:
    """The existing prefixes of AMENT_PREFIX_PATH, in order; OSError when the variable is unset or empty."""
    listed = os.environ.get(AMENT_PREFIX_PATH_ENV_VAR)
    if not listed:
        raise OSError(f"Environment variable '{AMENT_PREFIX_PATH_ENV_VAR}' is not set or empty")
    return [p for p in listed.split(os.pathsep) if p and os.path.exists(p)]


def _has_separator(name: str) -> bool:
    return "/" in name or "\\" in name


def _checked(resource_type: str, resource_name: str | None = None) -> None:
    assert resource_type, "The resource type must not be empty"
    if _has_separator(resource_type):
        raise InvalidResourceTypeNameError(f"Resource type '{resource_type}' is invalid")
    if resource_name is not None:
        assert resource_name, "The resource name must not be empty"
        if _has_separator(resource_name):
            raise InvalidResourceNameError(f"Resource name '{resource_name}' is invalid")


def _entry(resource_type: str, resource_name: str) -> tuple[Path, str] | None:
    for prefix in get_search_paths():
        candidate = Path(prefix, RESOURCE_INDEX_SUBFOLDER, resource_type, resource_name)
        if candidate.is_file():
            return candidate, prefix
    return None


def get_resource(resource_type: str, resource_name: str) -> tuple[str, str]:
    """(content, prefix) of the first prefix holding the resource; LookupError when none does."""
    _checked(resource_type, resource_name)
    found = _entry(resource_type, resource_name)
    if found is None:
        raise LookupError(f"Could not find the resource '{resource_name}' of type '{resource_type}'")
    path, prefix = found
    try:
        return path.read_text(), prefix
    except OSError as e:
        raise OSError(f"Could not open the resource '{resource_name}' of type '{resource_type}':\n{e}") from e


def has_resource(resource_type: str, resource_name: str) -> str | Literal[False]:
    """The prefix holding the resource, or False."""
    _checked(resource_type, resource_name)
    found = _entry(resource_type, resource_name)
    return found[1] if found is not None else False


def get_resources(resource_type: str) -> dict[str, str]:
    """Every resource name of the type, each with the first prefix holding it (hidden files and folders skipped)."""
    _checked(resource_type)
    names: dict[str, str] = {}
    for prefix in get_search_paths():
        folder = Path(prefix, RESOURCE_INDEX_SUBFOLDER, resource_type)
        if not folder.is_dir():
            continue
        for entry in folder.iterdir():
            if not entry.name.startswith(".") and not entry.is_dir():
                names.setdefault(entry.name, prefix)
    return names


def get_resource_types() -> set[str]:
    """The resource types (folders of the index) of every prefix."""
    types: set[str] = set()
    for prefix in get_search_paths():
        index = Path(prefix, RESOURCE_INDEX_SUBFOLDER)
        if index.is_dir():
            types.update(e.name for e in index.iterdir() if e.is_dir() and not e.name.startswith("."))
    return types
