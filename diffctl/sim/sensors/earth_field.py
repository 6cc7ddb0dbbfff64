"""The Earth's magnetic field as gz-sim 8's Magnetometer system gives it to magnetometers in a world with
`<spherical_coordinates>`: a 10° grid (latitudes −60…60, longitudes −180…180) of declination and inclination
in whole degrees and strength in whole centigauss, bilinearly interpolated exactly as its lookup does
(truncation toward zero, clamping, zero outside ±90/±180), then turned into north/east/down components.

Gazebo ships that grid as a constant table (PX4's, made from the World Magnetic Model around 2018). diffctl
computes the grid instead from the documented model: IGRF-13 (the `igrf-model` package) at epoch 2018.0 at sea
level, rounded as the table is; the two agree within a degree / a centigauss at the sampled points.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

SAMPLING_RES_DEG = 10.0
MIN_LAT_DEG, MAX_LAT_DEG = -60.0, 60.0
MIN_LON_DEG, MAX_LON_DEG = -180.0, 180.0
EPOCH_YEAR = 2018.0
ROWS, COLS = 13, 37


@lru_cache(maxsize=1)
def field_tables() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(declination deg, inclination deg, strength centigauss), each ROWS × COLS of whole numbers."""
    from igrf_model import IGRFModel

    model = IGRFModel.get(13).at(EPOCH_YEAR)
    decl, incl, strength = (np.zeros((ROWS, COLS)) for _ in range(3))
    for i in range(ROWS):
        for j in range(COLS):
            v = model.evaluate(MIN_LAT_DEG + i * SAMPLING_RES_DEG, MIN_LON_DEG + j * SAMPLING_RES_DEG, 0.0)
            decl[i, j] = round(v.declination)
            incl[i, j] = round(v.inclination)
            strength[i, j] = round(v.total_intensity / 1000.0)  # nT → centigauss (1 cG = 1000 nT)
    return decl, incl, strength


def _clamp_corner(value: float, low: float, high: float) -> tuple[float, int]:
    """The grid corner (clamped) and its index. The interpolation reads index + 1, so the last usable corner
    is one step inside the bound; gz-sim clamps the corner in place (a reference), so the interpolation
    weights are measured from the clamped corner too."""
    value = min(max(value, low), high - SAMPLING_RES_DEG)
    return value, int((value - low) / SAMPLING_RES_DEG)


def table_value(lat_deg: float, lon_deg: float, table: np.ndarray) -> float:
    """gz-sim's get_table_data: the grid bilinearly interpolated at a position, 0 outside the globe."""
    if lat_deg < -90.0 or lat_deg > 90.0 or lon_deg < -180.0 or lon_deg > 180.0:
        return 0.0
    # rounded toward zero to the grid, as C++'s static_cast<int> does
    min_lat = math.trunc(lat_deg / SAMPLING_RES_DEG) * SAMPLING_RES_DEG
    min_lon = math.trunc(lon_deg / SAMPLING_RES_DEG) * SAMPLING_RES_DEG
    min_lat, i = _clamp_corner(min_lat, MIN_LAT_DEG, MAX_LAT_DEG)
    min_lon, j = _clamp_corner(min_lon, MIN_LON_DEG, MAX_LON_DEG)
    sw, se, ne, nw = table[i, j], table[i, j + 1], table[i + 1, j + 1], table[i + 1, j]
    lat_scale = min(max((lat_deg - min_lat) / SAMPLING_RES_DEG, 0.0), 1.0)
    lon_scale = min(max((lon_deg - min_lon) / SAMPLING_RES_DEG, 0.0), 1.0)
    low = lon_scale * (se - sw) + sw
    high = lon_scale * (ne - nw) + nw
    return float(lat_scale * (high - low) + low)


def earth_field(lat_deg: float, lon_deg: float, units_gauss: bool = True, ned: bool = True) -> tuple[float, ...]:
    """The world magnetic field gz-sim sets for a sensor at a position: north/east/down (or east/north/up
    when `ned` is false), in gauss (or tesla when `units_gauss` is false; gz-sim's default is gauss, sent in
    the message's field_tesla all the same)."""
    decl_tab, incl_tab, strength_tab = field_tables()
    declination = math.radians(table_value(lat_deg, lon_deg, decl_tab))
    inclination = math.radians(table_value(lat_deg, lon_deg, incl_tab))
    strength_gauss = 0.01 * table_value(lat_deg, lon_deg, strength_tab)
    horizontal = math.cos(inclination) * (strength_gauss if units_gauss else 1e-4 * strength_gauss)
    north, east = horizontal * math.cos(declination), horizontal * math.sin(declination)
    down = math.tan(inclination) * horizontal
    return (north, east, down) if ned else (east, north, -down)
