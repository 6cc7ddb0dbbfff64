"""Magnetometers in a world placed on the Earth (<spherical_coordinates>) read the Earth's field as gz-sim 8's
Magnetometer system gives it: its 10° grid interpolated as it interpolates, in gauss and NED by default.

The grid diffctl computes from IGRF-13 is checked against rows of the constant table gz-sim 8 ships
(src/systems/magnetometer/Magnetometer.cc, three rows copied below as test data, BSD/Apache as gz-sim)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from sim_helpers import sdf_world
from test_sensor_details import MAG_RIG

from diffctl.sim.sensors.earth_field import earth_field, field_tables, table_value

# gz-sim 8's declination_table[6] (latitude 0), strength_table[6] (centigauss) and inclination_table[12] (60° N),
# longitudes −180…180 every 10°
GZ_DECLINATION_LAT0 = [
    10,
    9,
    9,
    9,
    9,
    9,
    9,
    8,
    7,
    3,
    -3,
    -10,
    -16,
    -20,
    -20,
    -18,
    -14,
    -9,
    -5,
    -2,
    1,
    2,
    0,
    -2,
    -4,
    -4,
    -3,
    -2,
    0,
    0,
    0,
    1,
    3,
    5,
    7,
    9,
    10,
]
GZ_STRENGTH_LAT0 = [
    34,
    33,
    32,
    32,
    31,
    31,
    31,
    30,
    30,
    30,
    29,
    28,
    27,
    27,
    27,
    28,
    29,
    31,
    32,
    33,
    33,
    33,
    34,
    35,
    37,
    39,
    41,
    42,
    43,
    42,
    41,
    40,
    39,
    38,
    36,
    35,
    34,
]
GZ_INCLINATION_LAT60 = [
    71,
    71,
    72,
    73,
    75,
    77,
    78,
    80,
    81,
    81,
    80,
    79,
    77,
    76,
    74,
    73,
    73,
    73,
    73,
    73,
    73,
    74,
    74,
    75,
    76,
    77,
    78,
    78,
    78,
    78,
    77,
    75,
    73,
    72,
    71,
    71,
    71,
]


def test_the_computed_grid_agrees_with_gazebos_table() -> None:
    declination, inclination, strength = field_tables()
    assert declination.shape == (13, 37)
    for ours, theirs in (
        (declination[6], GZ_DECLINATION_LAT0),
        (strength[6], GZ_STRENGTH_LAT0),
        (inclination[12], GZ_INCLINATION_LAT60),
    ):
        diff = np.abs(ours - np.array(theirs))
        assert diff.max() <= 1 and (diff == 0).mean() > 0.9, diff


def test_lookup_interpolates_as_gz_sim_does() -> None:
    table = np.arange(13 * 37, dtype=float).reshape(13, 37)
    assert table_value(0.0, 0.0, table) == table[6, 18]
    assert table_value(5.0, 5.0, table) == pytest.approx(table[6:8, 18:20].mean())
    # truncation toward zero then clamping: between -10 and -20 degrees the value stays the -10 row's
    assert table_value(-15.0, 0.0, table) == table[5, 18]
    assert table_value(75.0, 0.0, table) == table[12, 18]  # beyond the grid: its edge
    assert table_value(55.0, 0.0, table) == pytest.approx((table[11, 18] + table[12, 18]) / 2)
    assert table_value(95.0, 0.0, table) == 0.0  # off the globe: 0


def test_field_components_follow_gz_sims_formula() -> None:
    d, i, s = (
        math.radians(table_value(37.4, -122.1, t)) if k < 2 else 0.01 * table_value(37.4, -122.1, t)
        for k, t in enumerate(field_tables())
    )
    north, east, down = earth_field(37.4, -122.1)
    assert (north, east) == pytest.approx((s * math.cos(i) * math.cos(d), s * math.cos(i) * math.sin(d)))
    assert down == pytest.approx(math.tan(i) * s * math.cos(i)) and down > 0  # the field dips north of the equator
    assert earth_field(37.4, -122.1, units_gauss=False, ned=False) == pytest.approx(
        (east * 1e-4, north * 1e-4, -down * 1e-4)
    )


WORLD_ON_EARTH = """<spherical_coordinates><surface_model>EARTH_WGS84</surface_model>
  <world_frame_orientation>ENU</world_frame_orientation><latitude_deg>-22.986687</latitude_deg>
  <longitude_deg>-43.202501</longitude_deg><elevation>0</elevation><heading_deg>0</heading_deg>
</spherical_coordinates>"""


@pytest.mark.parametrize(
    "options", ["", "<use_units_gauss>false</use_units_gauss><use_earth_frame_ned>false</use_earth_frame_ned>"]
)
def test_a_magnetometer_in_a_world_on_the_earth_reads_the_earths_field(
    options: str, capfd: pytest.CaptureFixture[str]
) -> None:
    from diffctl.sim.runner import Simulation
    from diffctl.sim.sensors import Magnetometer
    from diffctl.sim.sensors.navsat import world_to_geodetic

    plugin = f'<plugin filename="gz-sim-magnetometer-system" name="gz::sim::systems::Magnetometer">{options}</plugin>'
    world = sdf_world(plugin + WORLD_ON_EARTH + MAG_RIG.format(yaw=0.0).replace("1e-8", "0"))
    sim = Simulation(world, rtf=0.0)
    try:
        assert "not simulated" not in capfd.readouterr().err  # the world's Magnetometer system is not ignored
        mag = next(s for s in sim.models["rig"].sensors if isinstance(s, Magnetometer))
        f = mag.sample(1_000_000)["field_tesla"]
    finally:
        sim.close()
    lat, lon, _ = world_to_geodetic(world.spherical_coordinates, (1.0, 2.0, 0.5))
    gauss, ned = not options, not options
    assert (f["x"], f["y"], f["z"]) == pytest.approx(earth_field(lat, lon, gauss, ned), rel=1e-9, abs=1e-15)
    # Rio de Janeiro: a southern field (up in NED, about 0.23 G in all); gauss unless told otherwise
    total = math.sqrt(f["x"] ** 2 + f["y"] ** 2 + f["z"] ** 2)
    assert total == pytest.approx(0.23 if gauss else 0.23e-4, rel=0.1)
    assert (f["z"] < 0) if ned else (f["z"] > 0)
