"""`diffctl image-bridge` as ros_gz_image's image_bridge: one gz→ROS Image entry per topic, same names, its qos
parameter, and its usage error."""

from __future__ import annotations

import subprocess
import sys

import pytest

from diffctl.bridge.config import QOS_PROFILES
from diffctl.bridge.image_bridge_cli import image_entries
from diffctl.errors import ConfigError


def test_each_topic_is_an_image_entry_on_the_same_name_gz_to_ros_never_lazy() -> None:
    entries, problem = image_entries(("/camera/front/image_raw", "/depth"), "sensor_data")
    assert problem is None
    assert [(e.ros_topic, e.gz_topic, e.ros_type, e.gz_type) for e in entries] == [
        ("/camera/front/image_raw", "/camera/front/image_raw", "sensor_msgs/msg/Image", "gz.msgs.Image"),
        ("/depth", "/depth", "sensor_msgs/msg/Image", "gz.msgs.Image"),
    ]
    assert all(e.direction.to_ros and not e.direction.to_gz and not e.lazy for e in entries)
    assert {e.qos for e in entries} == {QOS_PROFILES["SENSOR_DATA"]}
    assert image_entries(("/c",))[0][0].qos == QOS_PROFILES["DEFAULT"]
    assert image_entries(("/c",), "system_default")[0][0].qos == QOS_PROFILES["SYSTEM_DEFAULT"]


def test_an_unknown_qos_is_reported_and_the_default_used_as_image_bridge_does() -> None:
    entries, problem = image_entries(("/c",), "fast")
    assert problem == "Invalid QoS profile fast specified. Using default profile."
    assert entries[0].qos == QOS_PROFILES["DEFAULT"]


def test_no_topic_is_one_usage_error_exit_2() -> None:
    with pytest.raises(ConfigError, match="no image topic"):
        image_entries(())
    r = subprocess.run([sys.executable, "-m", "diffctl", "image-bridge"], capture_output=True, text=True, timeout=30)
    assert r.returncode == 2 and "image_bridge <topic>" in r.stderr and "Traceback" not in r.stderr
