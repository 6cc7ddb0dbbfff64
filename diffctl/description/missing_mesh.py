"""A mesh file that cannot be found: fatal for the file alone, but the model still loads, as in Gazebo.

Gazebo logs an error for a visual whose mesh it cannot find and draws nothing for it; for a collision, gz-sim's
physics system warns "Failed to load mesh" and creates the link without that collision (sim/Util.cc loadMesh,
systems/physics/Physics.cc). diffctl does the same: the shape is left out, with one error line naming the file,
line and URI, so a robot whose meshes are missing still spawns.
"""

from __future__ import annotations

from diffctl.errors import DescriptionError

_CONSEQUENCE = {
    "visual": "the model loads without this visual (nothing is drawn for it), as Gazebo does",
    "collision": "the model loads without this collision (nothing collides with it), as Gazebo does",
}
_reported: set[tuple[str | None, int | None, str]] = set()


class MeshNotFound(DescriptionError):
    """A mesh URI that resolves to no file."""


def report_missing_mesh(e: MeshNotFound, kind: str) -> None:
    """Print the error once per file, line and kind (models are read by several parts of one process)."""
    key = (e.source, e.line, kind)
    if key in _reported:
        return
    _reported.add(key)
    from diffctl.console import error

    error(f"{e}; {_CONSEQUENCE[kind]}")
