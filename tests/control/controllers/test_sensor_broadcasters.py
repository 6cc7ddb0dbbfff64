"""imu_sensor_broadcaster, range_sensor_broadcaster and force_torque_sensor_broadcaster driven directly (real client
nodes), with the sensor values, parameters and expected messages of their upstream tests (ros2_controllers jazzy:
test_imu_sensor_broadcaster, test_range_sensor_broadcaster, test_force_torque_sensor_broadcaster)."""

from __future__ import annotations

import struct

import pytest
from controller_harness import START_NS, activate, configure, hand_interfaces, make_controller, update

from diffctl.control.controller_interface import CallbackReturn
from diffctl.control.controllers.force_torque_sensor_broadcaster import ForceTorqueSensorBroadcaster
from diffctl.control.controllers.imu_sensor_broadcaster import IMUSensorBroadcaster
from diffctl.control.controllers.range_sensor_broadcaster import RangeSensorBroadcaster
from diffctl.control.lifecycle import State
from diffctl.errors import ParameterError

pytestmark = pytest.mark.usefixtures("client_bus")

IMU_VALUES = [0.1826, 0.3651, 0.5477, 0.7303, 5.5, 6.6, 7.7, 8.8, 9.9, 10.10]
FTS_VALUES = [1.1, 2.2, 3.3, 4.4, 5.5, 6.6]


def f32(x: float) -> float:
    return struct.unpack("<f", struct.pack("<f", x))[0]


def running(cls_, name: str, params: dict, values: dict | None = None):
    c = make_controller(cls_, name, params)
    assert c.on_configure(State.UNCONFIGURED) in (None, CallbackReturn.SUCCESS)
    configure(c)
    _, states = hand_interfaces(c, values)
    activate(c)
    return c, states


def test_imu_broadcaster_publishes_the_ten_values() -> None:
    # SensorName_Configure_Success, SensorName_Publish_Success
    names = ["orientation.x", "orientation.y", "orientation.z", "orientation.w", "angular_velocity.x",
             "angular_velocity.y", "angular_velocity.z", "linear_acceleration.x", "linear_acceleration.y",
             "linear_acceleration.z"]
    values = {f"imu_sensor/{n}": v for n, v in zip(names, IMU_VALUES, strict=True)}
    c, _ = running(IMUSensorBroadcaster, "imu_sensor_broadcaster",
                   {"sensor_name": "imu_sensor", "frame_id": "imu_sensor_frame",
                    "static_covariance_angular_velocity": [0.1 * k for k in range(9)]}, values)
    assert c.command_interface_configuration().type == "none"
    assert c.state_interface_configuration().names == list(values)
    update(c, START_NS, 0.01)
    (msg,) = c.probe.sent("/imu_sensor_broadcaster/imu")
    assert msg["header"]["frame_id"] == "imu_sensor_frame"
    assert msg["header"]["stamp"] == {"sec": START_NS // 10**9, "nanosec": 0}
    o, w, a = msg["orientation"], msg["angular_velocity"], msg["linear_acceleration"]
    assert [o["x"], o["y"], o["z"], o["w"], w["x"], w["y"], w["z"], a["x"], a["y"], a["z"]] == IMU_VALUES
    assert msg["orientation_covariance"] == [0.0] * 9 and msg["linear_acceleration_covariance"] == [0.0] * 9
    assert msg["angular_velocity_covariance"] == pytest.approx([0.1 * k for k in range(9)])


@pytest.mark.parametrize(("params", "field"), [({"frame_id": "f"}, "sensor_name"),
                                               ({"sensor_name": "imu"}, "frame_id"),
                                               ({"sensor_name": "imu", "frame_id": "f",
                                                 "static_covariance_orientation": [0.0] * 8},
                                                "static_covariance_orientation")])
def test_imu_broadcaster_parameters_as_its_yaml(params, field) -> None:
    with pytest.raises(ParameterError) as e:
        make_controller(IMUSensorBroadcaster, "imu_sensor_broadcaster", params)
    assert e.value.field == f"imu_sensor_broadcaster.{field}"


def test_range_broadcaster_publishes_range_with_the_sensor_description() -> None:
    # test/range_sensor_broadcaster_params.yaml; Publish_RangeBroadcaster_Success and the boundaries cases
    params = {"sensor_name": "range_sensor", "frame_id": "range_sensor_frame", "field_of_view": 0.1,
              "radiation_type": 1, "min_range": 0.10, "max_range": 7.0, "variance": 1.0}
    c, states = running(RangeSensorBroadcaster, "range_sensor_broadcaster", params, {"range_sensor/range": 3.1})
    for k, value in enumerate((3.1, 0.10, 4.0, 0.0, 6.0)):
        states["range_sensor/range"].value = value
        update(c, START_NS + k, 0.01)
        msg = c.probe.sent("/range_sensor_broadcaster/range")[-1]
        assert msg["range"] == f32(value) and msg["header"]["frame_id"] == "range_sensor_frame"
        assert (msg["radiation_type"], msg["field_of_view"], msg["min_range"], msg["max_range"], msg["variance"]) \
            == (1, f32(0.1), f32(0.1), f32(7.0), 1.0)
    # Configure_RangeBroadcaster_Error_1 / _2: no sensor name, no frame
    for missing in ("sensor_name", "frame_id"):
        c = make_controller(RangeSensorBroadcaster, "range_sensor_broadcaster",
                            {k: v for k, v in params.items() if k != missing})
        assert c.on_configure(State.UNCONFIGURED) is CallbackReturn.ERROR


def test_force_torque_broadcaster_offsets_multipliers_and_exports() -> None:
    # SensorName_Publish_Success_with_Offsets, then the multipliers set while it runs
    names = ["force.x", "force.y", "force.z", "torque.x", "torque.y", "torque.z"]
    values = {f"fts_sensor/{n}": v for n, v in zip(names, FTS_VALUES, strict=True)}
    offsets = [10.0, 30.0, -50.0, 1.0, -1.2, -5.2]
    params = {"sensor_name": "fts_sensor", "frame_id": "fts_sensor_frame"}
    params |= {f"offset.{n}": off for n, off in zip(names, offsets, strict=True)}
    name = "test_force_torque_sensor_broadcaster"
    c, _ = running(ForceTorqueSensorBroadcaster, name, params, values)
    update(c, START_NS, 0.01)
    msg = c.probe.sent(f"/{name}/wrench")[-1]
    got = [msg["wrench"][g][a] for g in ("force", "torque") for a in "xyz"]
    assert got == [v + off for v, off in zip(FTS_VALUES, offsets, strict=True)]
    exported = c.exported_state_interfaces
    assert [h.name for h in exported] == [f"{name}/fts_sensor/{n}" for n in names]
    assert [h.get_interface_name() for h in exported] == names
    assert [h.value for h in exported] == got
    assert not c.probe.sent(f"/{name}/wrench_filtered")
    # SensorName_Publish_Success_with_Multipliers (offsets back to zero), through the parameter service's path
    from diffctl.client.parameter import Parameter

    multipliers = [2.0, 0.5, -1.0, -2.0, 3.0, 0.0]
    node = c.get_node()
    node.set_parameters([Parameter(f"offset.{n}", value=0.0) for n in names]
                        + [Parameter(f"multiplier.{n}", value=m) for n, m in zip(names, multipliers, strict=True)])
    update(c, START_NS + 1, 0.01)
    msg = c.probe.sent(f"/{name}/wrench")[-1]
    assert [msg["wrench"][g][a] for g in ("force", "torque") for a in "xyz"] == \
        [v * m for v, m in zip(FTS_VALUES, multipliers, strict=True)]


def test_force_torque_broadcaster_by_axis_names() -> None:
    # InterfaceNames_Configure_Success / InterfaceNames_Success: two named axes, the others read 0
    params = {"interface_names.force.x": "fts_sensor/force.x", "interface_names.torque.z": "fts_sensor/torque.z",
              "frame_id": "fts_sensor_frame"}
    name = "test_force_torque_sensor_broadcaster"
    c, _ = running(ForceTorqueSensorBroadcaster, name, params,
                   {"fts_sensor/force.x": 1.1, "fts_sensor/torque.z": 6.6})
    assert c.state_interface_configuration().names == ["fts_sensor/force.x", "fts_sensor/torque.z"]
    assert [h.name for h in c.exported_state_interfaces] == [f"{name}/fts_sensor/force.x",
                                                             f"{name}/fts_sensor/torque.z"]
    update(c, START_NS, 0.01)
    w = c.probe.sent(f"/{name}/wrench")[-1]["wrench"]
    assert [w["force"]["x"], w["force"]["y"], w["torque"]["y"], w["torque"]["z"]] == [1.1, 0.0, 0.0, 6.6]
    # SensorName_InterfaceNames_Set / SensorName_IsEmpty_InterfaceNames_NotSet: one or the other, not both
    for bad in ({**params, "sensor_name": "fts_sensor"}, {"frame_id": "fts_sensor_frame"}):
        c = make_controller(ForceTorqueSensorBroadcaster, name, bad)
        assert c.on_configure(State.UNCONFIGURED) is CallbackReturn.ERROR
