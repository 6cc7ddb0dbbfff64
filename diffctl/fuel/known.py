"""The scenery nearly every Gazebo world includes from Fuel, shipped with diffctl so no world needs a download.

OpenRobotics' "Ground Plane" and "Sun" on fuel.gazebosim.org (and its older host names), any version, with a
space or `%20`. The SDF in models/ was written for diffctl from the documented content of those models (the
same entities gz-sim's examples/worlds/empty.sdf declares inline): model `ground_plane` with link `link`, and
the directional light `sun`.
"""

from __future__ import annotations

from pathlib import Path

from diffctl.fuel.uri import FuelRef

MODELS_DIR = Path(__file__).resolve().parent / "models"
FUEL_HOSTS = ("fuel.gazebosim.org", "fuel.ignitionrobotics.org", "api.ignitionfuel.org")
KNOWN = {("openrobotics", "ground plane"): "ground_plane", ("openrobotics", "sun"): "sun"}


def known_model(ref: FuelRef) -> Path | None:
    """diffctl's own copy of a well-known Fuel model, or None."""
    if ref.host.lower() not in FUEL_HOSTS:
        return None
    folder = KNOWN.get((ref.owner, ref.name.replace("%20", " ")))
    return MODELS_DIR / folder if folder else None
