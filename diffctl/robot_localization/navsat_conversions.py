"""Geodetic ↔ Cartesian for navsat_transform_node: UTM/UPS grid coordinates (with the meridian convergence)
and a local east-north-up tangent plane, through PROJ (pyproj) as upstream goes through GeographicLib.

Zones are chosen as GeographicLib's UTMUPS does: the standard UTM zone (with the Norway and Svalbard
exceptions) between 80°S and 84°N, UPS (zone 0) beyond.
"""

from __future__ import annotations

import functools
import math
import re
from typing import Any

UPS = 0
_BANDS = "CDEFGHJKLMNPQRSTUVWXX"  # 8° latitude bands from 80°S (X spans 12°)


def standard_zone(lat_deg: float, lon_deg: float) -> int:
    """The UTM zone of a point (1-60), or 0 for UPS near the poles."""
    if not (-80.0 <= lat_deg < 84.0):
        return UPS
    lon = (lon_deg + 180.0) % 360.0 - 180.0
    zone = int((lon + 180.0) // 6.0) + 1
    band = max(-10, min(9, math.floor(lat_deg / 8.0)))
    if band == 7 and zone == 31 and lon >= 3.0:  # southwest Norway
        zone = 32
    elif band == 9 and 0.0 <= lon < 42.0:  # Svalbard
        zone = 2 * int((lon + 183.0) / 12.0) + 1
    return min(zone, 60)


def parse_zone(text: str) -> tuple[int, bool]:
    """A grid zone designator as SetUTMZone takes it ("31U", "59G"; "A"/"B"/"Y"/"Z" for UPS) → (zone, north)."""
    m = re.fullmatch(r"\s*(\d{1,2})?\s*([A-Za-z])\s*", text)
    if m is None:
        raise ValueError(f"not a UTM grid zone designator: {text!r} (expected e.g. '31U')")
    number, letter = m.group(1), m.group(2).upper()
    if number is None:
        if letter not in "ABYZ":
            raise ValueError(f"{text!r}: a zone without a number must be a UPS zone (A, B, Y or Z)")
        return UPS, letter in "YZ"
    zone = int(number)
    if not 1 <= zone <= 60 or letter not in _BANDS or letter in "IO":
        raise ValueError(f"{text!r}: zone numbers are 1-60 and latitude bands C-X (without I and O)")
    return zone, letter >= "N"


@functools.lru_cache(maxsize=16)
def _proj(zone: int, north: bool) -> Any:
    from pyproj import Proj

    if zone == UPS:
        return Proj(proj="ups", ellps="WGS84", south=not north)
    return Proj(proj="utm", zone=zone, ellps="WGS84", south=not north)


def to_grid(lat_deg: float, lon_deg: float, zone: int | None = None) -> tuple[float, float, int, bool, float]:
    """(easting, northing, zone, north, meridian convergence in degrees) of a point, in its standard zone or
    the one given."""
    z = standard_zone(lat_deg, lon_deg) if zone is None or zone < 0 else zone
    north = lat_deg >= 0.0
    p = _proj(z, north)
    x, y = p(lon_deg, lat_deg)
    gamma = p.get_factors(lon_deg, lat_deg).meridian_convergence
    return float(x), float(y), z, north, float(gamma)


def from_grid(zone: int, north: bool, easting: float, northing: float) -> tuple[float, float]:
    """(latitude, longitude) in degrees of grid coordinates in `zone`."""
    lon, lat = _proj(zone, north)(easting, northing, inverse=True)
    return float(lat), float(lon)


class LocalCartesian:
    """East, north, up from a geodetic origin on the WGS84 ellipsoid (GeographicLib's LocalCartesian)."""

    def __init__(self, lat_deg: float = 0.0, lon_deg: float = 0.0, h_m: float = 0.0) -> None:
        self.reset(lat_deg, lon_deg, h_m)

    def reset(self, lat_deg: float, lon_deg: float, h_m: float) -> None:
        from pyproj import Transformer

        self._t = Transformer.from_pipeline(
            f"+proj=pipeline +step +proj=cart +ellps=WGS84 +step +proj=topocentric +ellps=WGS84 "
            f"+lat_0={lat_deg!r} +lon_0={lon_deg!r} +h_0={h_m!r}")

    def forward(self, lat_deg: float, lon_deg: float, h_m: float) -> tuple[float, float, float]:
        e, n, u = self._t.transform(lon_deg, lat_deg, h_m)
        return float(e), float(n), float(u)

    def reverse(self, e: float, n: float, u: float) -> tuple[float, float, float]:
        from pyproj.enums import TransformDirection

        lon, lat, h = self._t.transform(e, n, u, direction=TransformDirection.INVERSE)
        return float(lat), float(lon), float(h)
