"""ros_gz_bridge YAML and command-line entries: what is accepted, and how a bad entry is reported."""

from __future__ import annotations

from pathlib import Path

import pytest

from diffctl.bridge.cli import collect_entries
from diffctl.bridge.config import Direction, load_config, parse_cli_entry
from diffctl.errors import ConfigError

REPO = Path(__file__).resolve().parents[2]


def write(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "bridge.yaml"
    p.write_text(text)
    return p


def test_shipped_configs_load_and_control_variant_drops_what_ros2_control_publishes() -> None:
    full = {e.ros_topic: e for e in load_config(REPO / "config" / "bridge_config.yaml")}
    control = {e.ros_topic: e for e in load_config(REPO / "config" / "bridge_config_control.yaml")}
    assert {"/clock", "/joint_states", "/odom", "/tf", "/cmd_vel", "/scan", "/imu", "/camera/image_raw"} <= set(full)
    assert set(control) == set(full) - {"/joint_states", "/odom", "/tf", "/cmd_vel"}
    assert full["/cmd_vel"].direction is Direction.ROS_TO_GZ and full["/clock"].direction is Direction.GZ_TO_ROS
    assert full["/camera/image_raw"].lazy


def test_yaml_keys_defaults_and_spellings(tmp_path: Path) -> None:
    p = write(
        tmp_path,
        """
- topic_name: /chatter
  ros_type_name: std_msgs/String
  gz_type_name: ignition.msgs.StringMsg
- ros_topic_name: /odom
  gz_topic_name: /model/robot/odometry
  ros_type_name: nav_msgs/msg/Odometry
  gz_type_name: gz.msgs.Odometry
  direction: GZ_TO_ROS
  lazy: true
  publisher_queue: 5
  subscriber_queue: 3
""",
    )
    chatter, odom = load_config(p)
    assert (chatter.ros_topic, chatter.gz_topic, chatter.direction) == ("/chatter", "/chatter", Direction.BIDIRECTIONAL)
    assert (chatter.ros_type, chatter.gz_type) == ("std_msgs/msg/String", "gz.msgs.StringMsg")
    assert (chatter.lazy, chatter.publisher_queue, chatter.subscriber_queue) == (False, 10, 10)
    assert (odom.gz_topic, odom.lazy, odom.publisher_queue, odom.subscriber_queue) == (
        "/model/robot/odometry",
        True,
        5,
        3,
    )


def test_one_sided_topic_names_qos_profiles_and_queue_precedence(tmp_path: Path) -> None:
    p = write(
        tmp_path,
        """
- ros_topic_name: /scan
  ros_type_name: sensor_msgs/msg/LaserScan
  gz_type_name: gz.msgs.LaserScan
  direction: GZ_TO_ROS
  qos_profile: SENSOR_DATA
- gz_topic_name: /model/robot/cmd_vel
  ros_type_name: geometry_msgs/msg/TwistStamped
  gz_type_name: ignition.msgs.Twist
  direction: ROS_TO_GZ
  qos_profile: sensor_data
  subscriber_queue: "20"
- topic_name: /clock
  ros_type_name: rosgraph_msgs/msg/Clock
  gz_type_name: gz.msgs.Clock
  direction: BIDIRECTIONAL
  qos_profile: CLOCK
  lazy: "false"
- topic_name: /camera/camera_info
  ros_type_name: sensor_msgs/CameraInfo
  gz_type_name: gz.msgs.CameraInfo
  qos_profile: SYSTEM_DEFAULT
""",
    )
    scan, cmd, clock, info = load_config(p)
    # One of ros_topic_name / gz_topic_name names both sides, as parameter_bridge does.
    assert (scan.ros_topic, scan.gz_topic) == ("/scan", "/scan")
    assert (cmd.ros_topic, cmd.gz_topic) == ("/model/robot/cmd_vel", "/model/robot/cmd_vel")
    # SENSOR_DATA: depth 5, best effort; an explicit queue size wins over the preset's depth.
    assert (scan.qos.name, scan.qos.reliable, scan.publisher_queue, scan.subscriber_queue) == (
        "SENSOR_DATA",
        False,
        5,
        5,
    )
    assert (cmd.gz_type, cmd.subscriber_queue, cmd.publisher_queue) == ("gz.msgs.Twist", 20, 5)
    assert (clock.direction, clock.lazy, clock.publisher_queue, clock.qos.reliable) == (
        Direction.BIDIRECTIONAL,
        False,
        1,
        False,
    )
    assert (info.ros_type, info.qos.reliable, info.publisher_queue) == ("sensor_msgs/msg/CameraInfo", True, 10)


@pytest.mark.parametrize(
    ("body", "expected"),
    [
        (
            "  gz_type_name: gz.msgs.Odometry\n  direction: SIDEWAYS",
            r"bridge.yaml:7: entry 1 \(/odom\): direction 'SIDEWAYS' invalid; "
            r"valid: BIDIRECTIONAL, GZ_TO_ROS, ROS_TO_GZ",
        ),
        ("  direction: GZ_TO_ROS", r"entry 1 \(/odom\): missing key 'gz_type_name'"),
        (
            "  gz_type_name: gz.msgs.Odometry\n  qos_profile: FAST",
            r"bridge.yaml:7: entry 1 \(/odom\): qos_profile 'FAST' invalid; valid: SYSTEM_DEFAULT, .*SENSOR_DATA",
        ),
        (
            "  gz_type_name: gz.msgs.Twist",
            r"entry 1 \(/odom\): unsupported type pair nav_msgs/msg/Odometry <-> gz.msgs.Twist; "
            r"did you mean: geometry_msgs/msg/Twist<->gz.msgs.Twist, .*nav_msgs/msg/Odometry<->gz.msgs.Odometry",
        ),
        ("  gz_type_name: gz.msgs.Odometry\n  lazzy: true", r"unknown key 'lazzy' \(did you mean 'lazy'\?\)"),
        (
            "  gz_type_name: gz.msgs.Odometry\n  publisher_queue: 0",
            r"publisher_queue 0 invalid; valid: an integer >= 1",
        ),
        ("  gz_type_name: gz.msgs.Odometry\n  topic_name: /x", r"mutually exclusive"),
        (
            "  gz_type_name: gz.msgs.Odometry\n  gz_topic_name: /model/*/odom",
            r"bridge.yaml:7: .*gz topic name '/model/\*/odom' invalid",
        ),
    ],
)
def test_bad_entry_names_file_line_entry_and_valid_values(tmp_path: Path, body: str, expected: str) -> None:
    p = write(
        tmp_path,
        f"""- topic_name: /clock
  ros_type_name: rosgraph_msgs/msg/Clock
  gz_type_name: gz.msgs.Clock
- ros_topic_name: /odom
  ros_type_name: nav_msgs/msg/Odometry
{body}
""",
    )
    with pytest.raises(ConfigError, match=expected):
        load_config(p)


def test_file_level_errors(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match="not found"):
        load_config(tmp_path / "missing.yaml")
    with pytest.raises(ConfigError, match="YAML array of maps"):
        load_config(write(tmp_path, "topic_name: /clock\n"))
    with pytest.raises(ConfigError, match=r"bridge.yaml:2:\d+: malformed YAML"):
        load_config(write(tmp_path, "- a: [\n- b\n"))


@pytest.mark.parametrize(
    ("arg", "direction"),
    [
        ("/clock@rosgraph_msgs/msg/Clock[gz.msgs.Clock", Direction.GZ_TO_ROS),
        ("/cmd_vel@geometry_msgs/msg/Twist]gz.msgs.Twist", Direction.ROS_TO_GZ),
        ("/chatter@std_msgs/msg/String@gz.msgs.StringMsg", Direction.BIDIRECTIONAL),
        ("/camera/camera_info@sensor_msgs/msg/CameraInfo[ignition.msgs.CameraInfo", Direction.GZ_TO_ROS),
        ("/points@sensor_msgs/msg/PointCloud2[gz.msgs.PointCloudPacked", Direction.GZ_TO_ROS),
        ("/reset@std_msgs/msg/Empty]gz.msgs.Empty", Direction.ROS_TO_GZ),
    ],
)
def test_command_line_form(arg: str, direction: Direction) -> None:
    e = parse_cli_entry(arg)
    assert e.direction is direction and e.ros_topic == e.gz_topic == arg.split("@")[0]


@pytest.mark.parametrize(
    ("arg", "expected"),
    [
        ("/clock", r"argument 0 \(/clock\): no topic before '@'|no delimiter"),
        ("/clock@rosgraph_msgs/msg/Clock", "no delimiter between the ROS and the gz type"),
        ("/clock@rosgraph_msgs/msg/Clock[gz.msgs.Twist", "unsupported type pair"),
        ("/2fast@std_msgs/msg/String@gz.msgs.StringMsg", r"ROS topic name '/2fast' invalid"),
    ],
)
def test_command_line_form_errors(arg: str, expected: str) -> None:
    with pytest.raises(ConfigError, match=expected):
        parse_cli_entry(arg)


def test_config_file_parameter_and_expand_gz_topic_names(tmp_path: Path) -> None:
    clock = "  ros_type_name: rosgraph_msgs/msg/Clock\n  gz_type_name: gz.msgs.Clock\n"
    p = write(
        tmp_path,
        f"- topic_name: /clock\n{clock}- topic_name: odom_clock\n{clock}- gz_topic_name: ~/status\n"
        f"  ros_topic_name: status\n{clock}",
    )
    # rclcpp's expand_topic_or_service_name, as parameter_bridge applies it: absolute names stay.
    params = {"config_file": str(p), "expand_gz_topic_names": True}
    absolute, relative, private = collect_entries(
        ("rel@rosgraph_msgs/msg/Clock[gz.msgs.Clock",), None, params, "/robot1"
    )[:3]
    assert (absolute.ros_topic, absolute.gz_topic) == ("/clock", "/clock")
    assert (relative.ros_topic, relative.gz_topic) == ("odom_clock", "/robot1/odom_clock")
    assert private.gz_topic == "/robot1/ros_gz_bridge/status"
    cli = collect_entries(("rel@rosgraph_msgs/msg/Clock[gz.msgs.Clock",), None, params, "/robot1")[-1]
    assert cli.gz_topic == "rel"  # command-line entries are never expanded
    assert [e.gz_topic for e in collect_entries((), None, {"config_file": str(p)}, "/robot1")] == [
        "/clock",
        "odom_clock",
        "~/status",
    ]
    (_, top, _) = collect_entries((), None, params, None)
    assert top.gz_topic == "/odom_clock"
    with pytest.raises(ConfigError, match="nothing to bridge"):
        collect_entries((), None, {}, None)
    with pytest.raises(ConfigError, match="expand_gz_topic_names"):
        collect_entries((), str(p), {"expand_gz_topic_names": "maybe"}, None)


def test_entries_render_as_a_table() -> None:
    import io

    from diffctl.console import make_console

    buf = io.StringIO()
    make_console(buf, width=160).print(load_config(REPO / "config" / "bridge_config.yaml")[-1])
    text = buf.getvalue()
    assert "/camera/image_raw" in text and "sensor_msgs/msg/Image" in text and "<-" in text and "lazy" in text


def test_unsupported_pair_lists_only_its_neighbours() -> None:
    # a ROS type the table lacks, bridged to gz.msgs.NavSat: the error points at the NavSat pairs instead of
    # printing all the pairs on one line
    with pytest.raises(ConfigError) as e:
        parse_cli_entry("/gps/fix@my_msgs/msg/GpsFix[gz.msgs.NavSat")
    text = str(e.value)
    assert "did you mean: sensor_msgs/msg/NavSatFix<->gz.msgs.NavSat" in text
    assert "gz.msgs.Clock" not in text and len(text) < 300
    with pytest.raises(ConfigError, match=r"did you mean: sensor_msgs/msg/LaserScan<->gz.msgs.LaserScan \("):
        parse_cli_entry("/scan@sensor_msgs/msg/LaserScn[gz.msgs.LaserScan")
    with pytest.raises(ConfigError, match=r"no supported pair is close to it \(\d+ pairs supported"):
        parse_cli_entry("/x@foo_msgs/msg/Bar[gz.msgs.Qux")
