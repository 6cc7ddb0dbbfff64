"""navsat: geodesy against pymap3d (an independent WGS84 implementation), and a moving sensor in PyBullet."""

from __future__ import annotations

import math

import numpy as np
import pybullet as pb
import pymap3d
import pytest
from sim_helpers import build, sdf_world

from diffctl.description.model import SphericalCoordinates
from diffctl.description.sdf_loader import parse_world
from diffctl.sim.runner import Simulation
from diffctl.sim.sensors import NavSat
from diffctl.sim.sensors.navsat import world_to_geodetic
from diffctl.sim.sensors.topics import base_topic, outputs

PLACES = [
    SphericalCoordinates(latitude_deg=0.0, longitude_deg=0.0),
    SphericalCoordinates(latitude_deg=47.397742, longitude_deg=8.545594, elevation_m=488.0),  # Zürich
    SphericalCoordinates(latitude_deg=-33.8688, longitude_deg=151.2093, elevation_m=10.0),
    SphericalCoordinates(latitude_deg=64.1466, longitude_deg=-21.9426, elevation_m=-30.0),
]


@pytest.mark.parametrize("origin", PLACES)
@pytest.mark.parametrize("xyz", [(0.0, 0.0, 0.0), (120.0, -45.0, 3.0), (-2500.0, 1800.0, 150.0)])
def test_world_points_are_where_pymap3d_puts_them(origin: SphericalCoordinates, xyz: tuple) -> None:
    lat, lon, alt = world_to_geodetic(origin, xyz)
    ref = pymap3d.enu2geodetic(*xyz, origin.latitude_deg, origin.longitude_deg, origin.elevation_m)
    assert lat == pytest.approx(ref[0], abs=1e-8) and lon == pytest.approx(ref[1], abs=1e-8)
    assert alt == pytest.approx(ref[2], abs=1e-3)


def test_heading_turns_the_world_as_gz_math_does() -> None:
    """gz-math (SphericalCoordinates, LOCAL2) turns world x, y counter-clockwise by <heading_deg> into east,
    north: with 90° the world's +x points north and its +y west."""
    turned = SphericalCoordinates(latitude_deg=10.0, longitude_deg=20.0, heading_deg=90.0)
    for world_xy, enu in (((100.0, 0.0), (0.0, 100.0)), ((0.0, 100.0), (-100.0, 0.0))):
        lat, lon, _ = world_to_geodetic(turned, (*world_xy, 0.0))
        ref = pymap3d.enu2geodetic(*enu, 0.0, 10.0, 20.0, 0.0)
        assert (lat, lon) == (pytest.approx(ref[0], abs=1e-8), pytest.approx(ref[1], abs=1e-8))


WORLD = """<?xml version="1.0"?><sdf version="1.8"><world name="field">
  <spherical_coordinates><surface_model>EARTH_WGS84</surface_model>
    <world_frame_orientation>ENU</world_frame_orientation>
    <latitude_deg>47.397742</latitude_deg><longitude_deg>8.545594</longitude_deg>
    <elevation>488</elevation><heading_deg>0</heading_deg></spherical_coordinates>
  {models}
</world></sdf>"""
ROVER = """<model name="rover"><pose>30 40 2 0 0 0</pose><link name="body">
  <inertial><mass>1</mass><inertia><ixx>1</ixx><iyy>1</iyy><izz>1</izz><ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia>
  </inertial><gravity>false</gravity>
  <sensor name="gps" type="navsat"><update_rate>5</update_rate>{noise}</sensor></link></model>"""


def test_a_navsat_on_a_moving_body() -> None:
    world = parse_world(WORLD.format(models=ROVER.format(noise="")))
    assert world.spherical_coordinates is not None
    pw, ents = build(world)
    try:
        entity = ents["rover"]
        s = next(entity.model.sensors())
        assert [(o.topic, o.gz_type) for o in outputs(s, base_topic(s, "field", "rover"))] == [
            ("/world/field/model/rover/link/body/sensor/gps/navsat", "gz.msgs.NavSat")
        ]
        sensor = NavSat(entity, s, np.random.default_rng(0), world.spherical_coordinates)
        body = entity.link_frame("body")[0]
        pb.resetBaseVelocity(body, [1.5, -2.0, 0.25], [0, 0, 0], physicsClientId=entity.client)
        msg = sensor.sample(1_000_000_000)
        ref = pymap3d.enu2geodetic(30.0, 40.0, 2.0, 47.397742, 8.545594, 488.0)
        assert msg["latitude_deg"] == pytest.approx(ref[0], abs=1e-8)
        assert msg["longitude_deg"] == pytest.approx(ref[1], abs=1e-8)
        assert msg["altitude"] == pytest.approx(ref[2], abs=1e-3)
        vel = (msg["velocity_east"], msg["velocity_north"], msg["velocity_up"])
        assert vel == (pytest.approx(1.5), pytest.approx(-2.0), pytest.approx(0.25))
        assert msg["frame_id"] == "rover::body::gps" and msg["header"]["data"][0]["value"] == ["rover::body::gps"]
    finally:
        pw.close()


def test_navsat_noise_is_in_degrees_and_metres_as_gazebo() -> None:
    noise = """<navsat><position_sensing><horizontal><noise type="gaussian"><mean>0</mean><stddev>1e-5</stddev>
      </noise></horizontal><vertical><noise type="gaussian"><mean>0</mean><stddev>0.5</stddev></noise></vertical>
      </position_sensing></navsat>"""
    world = parse_world(WORLD.format(models=ROVER.format(noise=noise)))
    pw, ents = build(world)
    try:
        entity = ents["rover"]
        sensor = NavSat(entity, next(entity.model.sensors()), np.random.default_rng(3), world.spherical_coordinates)
        ref = pymap3d.enu2geodetic(30.0, 40.0, 2.0, 47.397742, 8.545594, 488.0)
        samples = [sensor.sample(i) for i in range(300)]
        lat = np.array([m["latitude_deg"] for m in samples])
        alt = np.array([m["altitude"] for m in samples])
        assert lat.std() == pytest.approx(1e-5, rel=0.25) and abs(lat.mean() - ref[0]) < 5e-6
        assert alt.std() == pytest.approx(0.5, rel=0.25) and abs(alt.mean() - ref[2]) < 0.2
    finally:
        pw.close()


def test_without_spherical_coordinates_a_navsat_publishes_nothing_and_says_why(capfd: pytest.CaptureFixture) -> None:
    body = ROVER.format(noise="").replace("<pose>30 40 2 0 0 0</pose>", "")
    sim = Simulation(sdf_world(body), rtf=0.0)
    try:
        assert not sim.models["rover"].sensors
        err = capfd.readouterr().err
        assert "navsat rover::body::gps" in err and "<spherical_coordinates>" in err
    finally:
        sim.close()


def test_gps_is_the_old_name_of_navsat() -> None:
    world = parse_world(WORLD.format(models=ROVER.format(noise="").replace('type="navsat"', 'type="gps"')))
    s = next(world.model("rover").sensors())
    assert (s.type, s.sdf_type) == ("navsat", "gps") and not world.model("rover").ignored
    assert math.isfinite(world.spherical_coordinates.latitude_deg)
