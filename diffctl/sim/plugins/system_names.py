"""The one alias table of Gazebo system plugin names: every spelling community SDF uses, to one kind.

gz-sim finds a system by `filename` (`gz-sim-X-system`, `libgz-sim-X-system.so`, `gz-sim8-X-system`, and the
older `ignition-gazebo-X-system` / `libignition-gazebo6-X-system.so`) and the class by `name`
(`gz::sim::systems::X`, `ignition::gazebo::systems::X`). A filename diffctl does not know is looked up by its
class name, so either spelling names the same system.
"""

from __future__ import annotations

import re

# kind (the filename stem between the gz-sim prefix and "-system") → C++ class name in gz::sim::systems
SYSTEM_CLASSES: dict[str, str] = {
    "physics": "Physics",
    "user-commands": "UserCommands",
    "scene-broadcaster": "SceneBroadcaster",
    "sensors": "Sensors",
    "imu": "Imu",
    "magnetometer": "Magnetometer",
    "air-pressure": "AirPressure",
    "navsat": "NavSat",
    "contact": "Contact",
    "diff-drive": "DiffDrive",
    "joint-state-publisher": "JointStatePublisher",
    "pose-publisher": "PosePublisher",
    "odometry-publisher": "OdometryPublisher",
    "linearbatteryplugin": "LinearBatteryPlugin",
    "thermal": "Thermal",
    "thermal-sensor": "ThermalSensor",
    "mecanum-drive": "MecanumDrive",
    "ackermann-steering": "AckermannSteering",
    "joint-position-controller": "JointPositionController",
    "joint-controller": "JointController",
    "velocity-control": "VelocityControl",
    "joint-trajectory-controller": "JointTrajectoryController",
    "apply-joint-force": "ApplyJointForce",
    "tracked-vehicle": "TrackedVehicle",
    "track-controller": "TrackController",
}
_BY_CLASS = {cls: kind for kind, cls in SYSTEM_CLASSES.items()}
_PREFIX = re.compile(r"^(?:gz-sim\d*-|ignition-gazebo\d*-)")
_CLASS_PREFIX = re.compile(r"^(?:gz::sim::systems::|ignition::gazebo::systems::|gz::sim::|ignition::gazebo::)")


def system_kind(filename: str, name: str = "") -> str:
    """`libignition-gazebo6-odometry-publisher-system.so` → `odometry-publisher`; a filename this table does
    not know is recognised by its class (`ignition::gazebo::systems::OdometryPublisher`); other plugins keep
    their stem (`gz_ros2_control-system` → `gz_ros2_control`)."""
    n = filename.rsplit("/", 1)[-1].removeprefix("lib").removesuffix(".so")
    stem = _PREFIX.sub("", n).removesuffix("-system")
    if stem in SYSTEM_CLASSES:
        return stem
    cls = _CLASS_PREFIX.sub("", name.strip())
    return _BY_CLASS.get(cls, stem)
