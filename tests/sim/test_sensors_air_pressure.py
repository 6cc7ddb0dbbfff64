"""air_pressure: the U.S. Standard Atmosphere's published pressures, and a sensor in a PyBullet world."""

from __future__ import annotations

import numpy as np
import pytest
from sim_helpers import build, sdf_world

from diffctl.description.sdf_loader import parse_model
from diffctl.errors import DescriptionError
from diffctl.sim.runner import Simulation
from diffctl.sim.sensors import AirPressure
from diffctl.sim.sensors.air_pressure import pressure_pa
from diffctl.sim.sensors.topics import base_topic, outputs


@pytest.mark.parametrize(
    # U.S. Standard Atmosphere 1976, pressure by geometric altitude (NOAA-S/T 76-1562, Table I).
    ("height_m", "pressure_pa_published"),
    [(0, 101325.0), (1000, 89876.0), (2000, 79501.0), (5000, 54048.0), (10000, 26500.0)],
)
def test_pressure_follows_the_standard_atmosphere(height_m: float, pressure_pa_published: float) -> None:
    assert pressure_pa(height_m) == pytest.approx(pressure_pa_published, abs=2.0)


def baro(extra: str = "") -> str:
    return f"""<model name="drone"><static>true</static><pose>0 0 100 0 0 0</pose><link name="body">
      <sensor name="baro" type="air_pressure"><pose>0 0 0.5 0 0 0</pose><update_rate>5</update_rate>
        <air_pressure><reference_altitude>400</reference_altitude>{extra}</air_pressure></sensor>
    </link></model>"""


def test_a_barometer_reads_its_height() -> None:
    pw, ents = build(sdf_world(baro()))
    try:
        s = next(ents["drone"].model.sensors())
        assert [(o.name, o.topic, o.gz_type) for o in outputs(s, base_topic(s, "test", "drone"))] == [
            ("air_pressure", "/world/test/model/drone/link/body/sensor/baro/air_pressure", "gz.msgs.FluidPressure")
        ]
        msg = AirPressure(ents["drone"], s, np.random.default_rng(0)).sample(3_000_000_000)
        assert msg["pressure"] == pytest.approx(pressure_pa(500.5)) and "variance" not in msg
        assert msg["header"]["data"] == [{"key": "frame_id", "value": ["drone::body::baro"]}]
    finally:
        pw.close()


def test_barometer_noise_and_the_variance_gazebo_writes() -> None:
    noise = "<pressure><noise type='gaussian'><mean>0</mean><stddev>4</stddev></noise></pressure>"
    pw, ents = build(sdf_world(baro(noise)))
    try:
        sensor = AirPressure(ents["drone"], next(ents["drone"].model.sensors()), np.random.default_rng(1))
        samples = [sensor.sample(i) for i in range(400)]
        values = np.array([m["pressure"] for m in samples])
        assert values.std() == pytest.approx(4.0, rel=0.2) and abs(values.mean() - pressure_pa(500.5)) < 1.5
        assert samples[0]["variance"] == 2.0  # sqrt(stddev), as gz-sensors fills it
    finally:
        pw.close()


def test_a_barometer_in_a_simulation_is_a_sensor_not_a_warning(capfd: pytest.CaptureFixture) -> None:
    # Gazebo needs the AirPressure system for it: accepted as what the simulator does natively.
    system = '<plugin filename="gz-sim-air-pressure-system" name="gz::sim::systems::AirPressure"/>'
    sim = Simulation(sdf_world(system + baro()), rtf=0.0)
    try:
        assert any(isinstance(s, AirPressure) for s in sim.models["drone"].sensors)
        err = capfd.readouterr().err
        assert "baro" not in err and "air-pressure" not in err
    finally:
        sim.close()


def test_a_bad_reference_altitude_names_the_element() -> None:
    bad = """<sdf version="1.8"><model name="m"><static>true</static><link name="l">
      <sensor name="b" type="air_pressure"><air_pressure><reference_altitude>high</reference_altitude>
      </air_pressure></sensor></link></model></sdf>"""
    with pytest.raises(DescriptionError, match="reference_altitude"):
        parse_model(bad)
