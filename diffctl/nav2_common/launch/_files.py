"""Reading the source file a nav2_common substitution edits, and writing the copy it hands back."""

from __future__ import annotations

import tempfile
from typing import Any

import yaml

from diffctl.launch.substitutions import SubstitutionFailure


def read_text(path: str, who: str) -> str:
    try:
        with open(path, encoding="utf-8") as f:
            return f.read()
    except (OSError, UnicodeDecodeError) as e:
        raise SubstitutionFailure(f"{who}: cannot read {path!r}: {e.strerror if isinstance(e, OSError) else e}") from e


def read_yaml(path: str, who: str) -> Any:
    try:
        return yaml.safe_load(read_text(path, who))
    except yaml.YAMLError as e:
        raise SubstitutionFailure(f"{who}: {path!r} is not valid YAML: {' '.join(str(e).split())}") from e


def write_copy(text: str) -> str:
    """A new file in the temporary folder that outlives the launch (nodes read it later), as upstream's."""
    with tempfile.NamedTemporaryFile(mode="w", delete=False, encoding="utf-8") as out:
        out.write(text)
    return out.name
