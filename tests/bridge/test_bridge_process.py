"""`diffctl bridge` as a real process on a real router: each direction, every pair, no echo, lazy, bad input."""

from __future__ import annotations

import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import yaml
import zenoh
from bridge_samples import GZ_SAMPLES, plain, same

from diffctl.bridge import type_pairs
from diffctl.bus import gz
from diffctl.interfaces import types
from tests.probe import Probe
from tests.waiting import wait_for


def output_of(procs, proc: subprocess.Popen) -> str:
    procs.stop(proc)
    return proc.stdout.read()


def bridge_up(node: Probe, topic: str, kind: str = "pub") -> bool:
    ents = node.graph.publishers(topic) if kind == "pub" else node.graph.subscribers(topic)
    return any(e.node == "ros_gz_bridge" for e in ents)


def test_every_pair_both_directions(router: str, procs, tmp_path: Path) -> None:
    pairs = sorted(GZ_SAMPLES)
    config = []
    for i, (ros_type, gz_type) in enumerate(pairs):
        common = {"ros_type_name": ros_type, "gz_type_name": gz_type}
        config.append({"topic_name": f"/pairs/out{i}", **common, "direction": "GZ_TO_ROS"})
        config.append(
            {"ros_topic_name": f"/pairs/in{i}", "gz_topic_name": f"/sim/in{i}", **common, "direction": "ROS_TO_GZ"}
        )
    cfg = tmp_path / "pairs.yaml"
    cfg.write_text(yaml.safe_dump(config))
    bridge = procs.diffctl("bridge", "--config", str(cfg))

    node = Probe("pairs_probe")
    lock = threading.Lock()
    got_ros: dict[int, object] = {}
    got_gz: dict[int, dict] = {}
    gz_pubs, ros_pubs, expected_ros, keep = [], [], [], []
    for i, (ros_type, gz_type) in enumerate(pairs):
        pair = type_pairs.lookup(ros_type, gz_type)
        expected_ros.append(pair.convert_to_ros(GZ_SAMPLES[(ros_type, gz_type)]))

        def on_ros(msg: object, i: int = i) -> None:
            with lock:
                got_ros[i] = msg

        def on_gz(sample: zenoh.Sample, i: int = i, gz_type: str = gz_type) -> None:
            with lock:
                got_gz[i] = gz.decode(sample.payload.to_bytes(), gz_type)[1]

        keep.append(node.create_subscription(f"/pairs/out{i}", ros_type, on_ros))
        keep.append(node.session.declare_subscriber(gz.key(f"/sim/in{i}"), on_gz))
        gz_pubs.append(node.session.declare_publisher(gz.key(f"/pairs/out{i}")))
        ros_pubs.append(node.create_publisher(f"/pairs/in{i}", ros_type))

    def send() -> None:
        for i, (ros_type, gz_type) in enumerate(pairs):
            if i not in got_ros:
                gz_pubs[i].put(gz.encode(gz_type, GZ_SAMPLES[(ros_type, gz_type)]))
            if i not in got_gz:
                ros_pubs[i].publish(expected_ros[i])

    try:
        assert wait_for(lambda: len(got_ros) == len(got_gz) == len(pairs), 15.0, send), (
            f"missing gz->ros {sorted(set(range(len(pairs))) - set(got_ros))}, "
            f"ros->gz {sorted(set(range(len(pairs))) - set(got_gz))}; bridge said:\n" + output_of(procs, bridge)
        )
        for i, (ros_type, gz_type) in enumerate(pairs):
            pair = type_pairs.lookup(ros_type, gz_type)
            assert same(types.to_dict(got_ros[i]), types.to_dict(expected_ros[i])), ros_type
            assert plain(got_gz[i]) == plain(pair.convert_to_gz(expected_ros[i])), gz_type
    finally:
        node.close()
    assert procs.stop(bridge) == 0


def test_bidirectional_entry_never_echoes(router: str, procs) -> None:
    bridge = procs.diffctl("bridge", "/chatter@std_msgs/msg/String@gz.msgs.StringMsg")
    node = Probe("echo_probe")
    ros_seen: list[str] = []
    gz_seen: list[str] = []
    node.create_subscription("/chatter", "std_msgs/msg/String", lambda m: ros_seen.append(m.data))
    gz_sub = node.session.declare_subscriber(  # noqa: F841 (kept alive)
        gz.key("/chatter"),
        lambda s: gz_seen.append(gz.decode(s.payload.to_bytes())[1]["data"]),
        allowed_origin=zenoh.Locality.REMOTE,
    )
    ros_pub = node.create_publisher("/chatter", "std_msgs/msg/String")
    gz_pub = node.session.declare_publisher(gz.key("/chatter"))
    try:
        assert wait_for(lambda: "ros-warmup" in gz_seen, 10.0, lambda: ros_pub.publish({"data": "ros-warmup"}))
        assert wait_for(
            lambda: "gz-warmup" in ros_seen,
            10.0,
            lambda: gz_pub.put(gz.encode("gz.msgs.StringMsg", {"data": "gz-warmup"})),
        )
        ros_pub.publish({"data": "from-ros"})
        gz_pub.put(gz.encode("gz.msgs.StringMsg", {"data": "from-gz"}))
        assert wait_for(lambda: "from-ros" in gz_seen and "from-gz" in ros_seen, 5.0)
        time.sleep(0.5)  # time for an echo, were there one
        # Each message crosses once; nothing the bridge published comes back to the side it came from.
        assert gz_seen.count("from-ros") == 1 and ros_seen.count("from-gz") == 1
        assert ros_seen.count("from-ros") == 1  # the probe's own local copy only
        assert not any(s.startswith("gz-") or s == "from-gz" for s in gz_seen)
    finally:
        node.close()
    assert procs.stop(bridge) == 0


def test_lazy_entries_move_nothing_until_someone_subscribes(router: str, procs, tmp_path: Path) -> None:
    cfg = tmp_path / "lazy.yaml"
    cfg.write_text(
        yaml.safe_dump(
            [
                {
                    "ros_topic_name": "/camera/image_raw",
                    "gz_topic_name": "/camera",
                    "ros_type_name": "sensor_msgs/msg/Image",
                    "gz_type_name": "gz.msgs.Image",
                    "direction": "GZ_TO_ROS",
                    "lazy": True,
                },
                {
                    "ros_topic_name": "/cmd_vel",
                    "gz_topic_name": "/model/robot/cmd_vel",
                    "lazy": True,
                    "ros_type_name": "geometry_msgs/msg/Twist",
                    "gz_type_name": "gz.msgs.Twist",
                    "direction": "ROS_TO_GZ",
                },
            ]
        )
    )
    bridge = procs.diffctl("bridge", "--ros-args", "-p", f"config_file:={cfg}")
    node = Probe("lazy_probe")
    image = GZ_SAMPLES[("sensor_msgs/msg/Image", "gz.msgs.Image")]
    cam_pub = node.session.declare_publisher(gz.key("/camera"))
    cmd_pub = node.create_publisher("/cmd_vel", "geometry_msgs/msg/Twist")
    try:
        assert wait_for(lambda: bridge_up(node, "/camera/image_raw"), 10.0), "bridge never published its ROS side"
        # gz→ROS: nobody on /camera/image_raw, so the bridge holds no gz subscription at all.
        time.sleep(0.5)
        assert not cam_pub.matching_status.matching
        # ROS→gz: nobody on gz /model/robot/cmd_vel, so the bridge does not subscribe to /cmd_vel.
        assert cmd_pub.subscription_count == 0

        images: list[object] = []
        sub = node.create_subscription("/camera/image_raw", "sensor_msgs/msg/Image", images.append)
        assert wait_for(lambda: cam_pub.matching_status.matching, 5.0)
        assert wait_for(lambda: bool(images), 5.0, lambda: cam_pub.put(gz.encode("gz.msgs.Image", image)))
        assert images[0].encoding == "rgb8"
        sub.close()
        assert wait_for(lambda: not cam_pub.matching_status.matching, 5.0)

        twists: list[dict] = []
        gz_sub = node.session.declare_subscriber(
            gz.key("/model/robot/cmd_vel"), lambda s: twists.append(gz.decode(s.payload.to_bytes())[1])
        )
        assert wait_for(lambda: cmd_pub.subscription_count == 1, 5.0)
        assert wait_for(
            lambda: bool(twists), 5.0, lambda: cmd_pub.publish({"linear": {"x": 0.4}, "angular": {"z": 0.2}})
        )
        assert twists[0]["linear"]["x"] == 0.4 and twists[0]["angular"]["z"] == 0.2
        gz_sub.undeclare()
        assert wait_for(lambda: cmd_pub.subscription_count == 0, 5.0)
    finally:
        node.close()
    assert procs.stop(bridge) == 0


def test_bad_entry_is_exit_2_naming_it_and_starts_nothing(tmp_path: Path) -> None:
    cfg = tmp_path / "bad.yaml"
    cfg.write_text(
        "- topic_name: /clock\n  ros_type_name: rosgraph_msgs/msg/Clock\n  gz_type_name: gz.msgs.Clock\n"
        "- topic_name: /odom\n  ros_type_name: nav_msgs/msg/Odometry\n  gz_type_name: gz.msgs.Odometry\n"
        "  direction: UPWARDS\n"
    )
    # No router answers here: reaching the bus would give a different error.
    env_router = "tcp/127.0.0.1:9"
    r = subprocess.run(
        [sys.executable, "-m", "diffctl", "bridge", "--config", str(cfg)],
        capture_output=True,
        text=True,
        timeout=30,
        env={**__import__("os").environ, "DIFFCTL_ROUTER": env_router},
    )
    assert r.returncode == 2
    err = " ".join(r.stderr.split())
    assert "bad.yaml:7: entry 1 (/odom): direction 'UPWARDS' invalid; valid: BIDIRECTIONAL, GZ_TO_ROS, ROS_TO_GZ" in err
    assert "Traceback" not in r.stderr and "router" not in err


def test_camera_info_point_cloud_and_full_size_images_from_a_fake_gz_camera(router: str, procs, tmp_path: Path) -> None:
    """An rgbd camera's outputs as a user's bridge YAML names them (ignition.* spelling, qos_profile); the
    rendered ones are fetched from gz only while someone on the ROS side subscribes."""
    cfg = tmp_path / "camera.yaml"
    cfg.write_text(
        "- ros_topic_name: /camera/camera_info\n  gz_topic_name: /rgbd/camera_info\n"
        "  ros_type_name: sensor_msgs/msg/CameraInfo\n  gz_type_name: ignition.msgs.CameraInfo\n"
        "  direction: GZ_TO_ROS\n"
        "- ros_topic_name: /camera/points\n  gz_topic_name: /rgbd/points\n"
        "  ros_type_name: sensor_msgs/msg/PointCloud2\n  gz_type_name: gz.msgs.PointCloudPacked\n"
        "  direction: GZ_TO_ROS\n  qos_profile: SENSOR_DATA\n"
        "- ros_topic_name: /camera/image\n  gz_topic_name: /rgbd/image\n"
        "  ros_type_name: sensor_msgs/msg/Image\n  gz_type_name: gz.msgs.Image\n"
        "  direction: GZ_TO_ROS\n  lazy: false\n  publisher_queue: 2\n"
    )
    bridge = procs.diffctl("bridge", "--ros-args", "-p", f"config_file:={cfg}")
    width, height = 640, 480
    rgb = np.random.default_rng(7).integers(0, 256, (height, width, 3), dtype=np.uint8)
    cloud = np.zeros((height // 4) * (width // 4) * 6, dtype=np.float32)  # 24-byte points, as the sim packs them
    cloud[0::6], cloud[1::6], cloud[2::6] = 1.5, -0.25, np.linspace(0.0, 2.0, len(cloud) // 6)
    info = GZ_SAMPLES[("sensor_msgs/msg/CameraInfo", "gz.msgs.CameraInfo")]
    samples = {
        "/rgbd/camera_info": ("gz.msgs.CameraInfo", dict(info, width=width, height=height)),
        "/rgbd/points": (
            "gz.msgs.PointCloudPacked",
            dict(
                GZ_SAMPLES[("sensor_msgs/msg/PointCloud2", "gz.msgs.PointCloudPacked")],
                width=width // 4,
                height=height // 4,
                row_step=24 * (width // 4),
                data=cloud.tobytes(),
            ),
        ),
        "/rgbd/image": (
            "gz.msgs.Image",
            {
                "header": gz.header(77, frame_id="robot::camera_link::rgbd"),
                "width": width,
                "height": height,
                "step": 3 * width,
                "pixel_format_type": "RGB_INT8",
                "data": rgb.tobytes(),
            },
        ),
    }
    node = Probe("camera_probe")
    gz_pubs = {t: node.session.declare_publisher(gz.key(t)) for t in samples}
    got: dict[str, object] = {}
    try:
        assert wait_for(lambda: bridge_up(node, "/camera/image"), 10.0), output_of(procs, bridge)
        assert wait_for(lambda: gz_pubs["/rgbd/camera_info"].matching_status.matching, 5.0)
        time.sleep(0.5)
        # Nobody wants frames yet: the bridge holds no subscription on the rendered topics, so the sim renders none.
        assert not gz_pubs["/rgbd/image"].matching_status.matching
        assert not gz_pubs["/rgbd/points"].matching_status.matching

        for topic, ros_type in (
            ("/camera/camera_info", "sensor_msgs/msg/CameraInfo"),
            ("/camera/points", "sensor_msgs/msg/PointCloud2"),
            ("/camera/image", "sensor_msgs/msg/Image"),
        ):
            node.create_subscription(topic, ros_type, lambda m, topic=topic: got.setdefault(topic, m))

        def send() -> None:
            for t, (gz_type, sample) in samples.items():
                gz_pubs[t].put(gz.encode(gz_type, sample))

        assert wait_for(lambda: len(got) == 3, 15.0, send), f"got {sorted(got)}; bridge said:\n" + output_of(
            procs, bridge
        )
        image = got["/camera/image"]
        assert (image.width, image.height, image.encoding, image.step) == (width, height, "rgb8", 3 * width)
        assert image.header.frame_id == "robot/camera_link/rgbd"
        assert np.array_equal(np.asarray(image.data).reshape(height, width, 3), rgb)
        cam = got["/camera/camera_info"]
        assert (cam.width, cam.distortion_model, cam.k.tolist()) == (width, "plumb_bob", info["intrinsics"]["k"])
        points = got["/camera/points"]
        assert (points.width, points.height, points.point_step) == (width // 4, height // 4, 24)
        assert [f.name for f in points.fields] == ["x", "y", "z", "rgb"]
        assert np.array_equal(np.frombuffer(np.asarray(points.data).tobytes(), dtype=np.float32), cloud)
    finally:
        node.close()
    assert procs.stop(bridge) == 0


def test_unsupported_pair_is_one_line_naming_the_entry_and_the_supported_pairs(tmp_path: Path) -> None:
    cfg = tmp_path / "user.yaml"
    cfg.write_text(
        "- topic_name: /clock\n  ros_type_name: rosgraph_msgs/msg/Clock\n  gz_type_name: gz.msgs.Clock\n"
        "  direction: GZ_TO_ROS\n"
        "- ros_topic_name: /battery\n  gz_topic_name: /model/robot/battery/state\n"
        "  ros_type_name: sensor_msgs/msg/Temperature\n  gz_type_name: gz.msgs.Double\n"
    )
    env = {**__import__("os").environ, "DIFFCTL_ROUTER": "tcp/127.0.0.1:9"}
    for args in (["--config", str(cfg)], ["/battery@sensor_msgs/msg/Temperature[gz.msgs.Double"]):
        r = subprocess.run(
            [sys.executable, "-m", "diffctl", "bridge", *args], capture_output=True, text=True, timeout=30, env=env
        )
        assert r.returncode == 2, r.stderr
        lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
        err = " ".join(r.stderr.split())
        assert "unsupported type pair sensor_msgs/msg/Temperature <-> gz.msgs.Double" in err
        assert "/battery" in err and "did you mean: std_msgs/msg/Float64<->gz.msgs.Double" in err
        assert "Traceback" not in r.stderr and len(lines) <= 2, r.stderr


def test_malformed_gz_samples_are_dropped_with_one_warning_and_the_bridge_goes_on(router: str, procs) -> None:
    bridge = procs.diffctl("bridge", "/camera@sensor_msgs/msg/Image[gz.msgs.Image")
    node = Probe("malformed_probe")
    images: list[object] = []
    node.create_subscription("/camera", "sensor_msgs/msg/Image", images.append)
    cam = node.session.declare_publisher(gz.key("/camera"))
    good = GZ_SAMPLES[("sensor_msgs/msg/Image", "gz.msgs.Image")]
    bad = [
        b'{"@type":"gz.msgs.Image","width":2}',  # the old JSON form
        b"\x92\xc1",
        gz.encode("gz.msgs.Twist", {}),
        gz.encode("gz.msgs.Image", dict(good, data=b"short")),
        gz.encode("gz.msgs.Image", dict(good, pixel_format_type="YUV")),
        gz.encode("gz.msgs.Image", dict(good, width=-1, step=-3, data=b"")),
    ]
    try:
        assert wait_for(lambda: cam.matching_status.matching, 10.0), output_of(procs, bridge)
        for _ in range(20):
            for payload in bad:
                cam.put(payload)
        assert wait_for(lambda: bool(images), 10.0, lambda: cam.put(gz.encode("gz.msgs.Image", good)))
        assert images[0].data.tolist() == list(range(12))
    finally:
        node.close()
    assert procs.stop(bridge) == 0
    out = bridge.stdout.read()
    assert "dropped a sample on gz /camera" in out and "Traceback" not in out
    assert out.count("dropped a sample on gz /camera") < 5  # throttled, not one line per sample


def test_a_non_lazy_entry_keeps_its_gz_side_and_converts_only_while_ros_listens(router: str, procs) -> None:
    """ros_gz_bridge's default (not lazy): the gz subscription stays whether or not anyone listens on the ROS
    side. What nobody would receive is not converted or put: the first sample a late subscriber gets is the
    publisher's first (sequence number 1), although many passed through before."""
    bridge = procs.diffctl("bridge", "/imu@sensor_msgs/msg/Imu[gz.msgs.IMU")
    node = Probe("unheard_probe")
    imu_pub = node.session.declare_publisher(gz.key("/imu"))
    fields = GZ_SAMPLES[("sensor_msgs/msg/Imu", "gz.msgs.IMU")]
    sample = gz.encode("gz.msgs.IMU", fields)
    try:
        assert wait_for(lambda: imu_pub.matching_status.matching, 10.0), output_of(procs, bridge)
        for _ in range(50):
            imu_pub.put(sample)
        time.sleep(0.3)
        assert imu_pub.matching_status.matching  # still subscribed on the gz side
        got: list[tuple[object, object]] = []
        node.create_subscription("/imu", "sensor_msgs/msg/Imu", lambda m, i: got.append((m, i)), with_info=True)
        assert wait_for(lambda: bool(got), 10.0, lambda: imu_pub.put(sample))
        msg, info = got[0]
        assert info.sequence_number == 1, info
        assert msg.linear_acceleration.z == fields["linear_acceleration"]["z"]
    finally:
        node.close()
    assert procs.stop(bridge) == 0


def test_the_bridge_gz_side_is_listed_by_gz_topic_as_gz_transport_lists_it(router: str, procs) -> None:
    """ros_gz_bridge advertises a gz publisher for each ROS→gz entry and subscribes for each gz→ROS one, so
    `gz topic -l` lists both and `gz topic -i` names their types; they go when the bridge does."""
    import os

    gz_cli = [sys.executable, "-c", "from diffctl.gz.cli import main; main()"]

    def gz_run(*args: str) -> str:
        res = subprocess.run([*gz_cli, *args], capture_output=True, text=True, timeout=30, env=os.environ.copy())
        return res.stdout

    bridge = procs.diffctl(
        "bridge",
        "/model/car/cmd_vel@geometry_msgs/msg/Twist]gz.msgs.Twist",
        "/detections@vision_msgs/msg/Detection2DArray[gz.msgs.AnnotatedAxisAligned2DBox_V",
    )
    expected = {"/model/car/cmd_vel", "/detections"}
    assert wait_for(lambda: expected <= set(gz_run("topic", "-l").split()), 20.0), output_of(procs, bridge)
    info = gz_run("topic", "-i", "-t", "/model/car/cmd_vel")
    assert info.startswith("Publishers [Address, Message Type]:") and ", gz.msgs.Twist" in info, info
    assert "No subscribers on topic [/model/car/cmd_vel]" in info
    info = gz_run("topic", "-i", "-t", "/detections")
    assert "No publishers on topic [/detections]" in info and ", gz.msgs.AnnotatedAxisAligned2DBox_V" in info, info
    assert procs.stop(bridge) == 0
    assert wait_for(lambda: not expected & set(gz_run("topic", "-l").split()), 10.0)
