"""Two-stage robot_localization with GPS, as its dual_ekf_navsat example composes it: an odom-frame EKF
(wheel odometry + gyro), a map-frame EKF (the same plus odometry/gps) and navsat_transform_node turning
fixes into map-frame poses — three real processes on sim time, fed a simulated drive along an arc.

The oracle is independent of robot_localization's code: the drive's ground truth, its GPS fixes and the
geodetic checks all go through pymap3d (WGS84 east-north-up), while navsat_transform_node works in the UTM
grid through PROJ. The wheel odometry over-reads by 4 %, so dead reckoning drifts; the map estimate must
stay on the truth, and gps/filtered must put it back at the right latitude and longitude.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pymap3d
import pytest
import yaml

from diffctl.interfaces import types
from tests.robot_localization.harness import SEC, Driver, quat_rpy, yaw_of

pytestmark = pytest.mark.slow
F, T = False, True
DATUM = (48.8584, 2.2945, 35.0)  # latitude, longitude, altitude of the start
HEADING = 0.3  # rad from east, counter-clockwise
SPEED, TURN = 1.0, 0.08  # m/s, rad/s
ODOM_SCALE = 1.04
ANTENNA = (0.5, 0.0, 0.3)  # gps_link in base_link
GPS_SIGMA, GYRO_SIGMA = 0.1, 0.002
ODOM_TWIST = [F, F, F, F, F, F, T, T, F, F, F, T, F, F, F]
IMU_YAW_AND_RATE = [F, F, F, F, F, T, F, F, F, F, F, T, F, F, F]


REST_S = 3.0  # standing still first, as a robot does while navsat_transform_node takes its datum


def truth(t: float) -> tuple[float, float, float]:
    """x (east), y (north), yaw of the drive t seconds after the start."""
    yaw = HEADING + TURN * max(0.0, t - REST_S)
    r = SPEED / TURN
    return r * (math.sin(yaw) - math.sin(HEADING)), -r * (math.cos(yaw) - math.cos(HEADING)), yaw


def _params(tmp: Path) -> Path:
    # The estimates must not depend on how late a loaded machine delivers the samples against /clock (which this
    # test nudges on while it waits): no prediction past the last measurement (a long sensor_timeout), so an
    # output stamped t has fused the samples up to t, and late samples rolled back and replayed
    # (smooth_lagged_data), as upstream's ekf.yaml advises for late data.
    common = {"use_sim_time": True, "frequency": 30.0, "two_d_mode": True, "publish_tf": True,
              "sensor_timeout": 30.0, "smooth_lagged_data": True, "history_length": 5.0,
              "map_frame": "map", "odom_frame": "odom", "base_link_frame": "base_link",
              "odom0": "/wheel/odometry", "odom0_config": ODOM_TWIST, "imu0": "/imu",
              "imu0_config": IMU_YAW_AND_RATE}
    config = {
        "ekf_filter_node_odom": {"ros__parameters": {**common, "world_frame": "odom"}},
        "ekf_filter_node_map": {"ros__parameters": {
            **common, "world_frame": "map", "odom1": "/odometry/gps",
            "odom1_config": [T, T, F, F, F, F, F, F, F, F, F, F, F, F, F]}},
        "navsat_transform": {"ros__parameters": {"use_sim_time": True, "frequency": 30.0,
                                                 "zero_altitude": True, "publish_filtered_gps": True,
                                                 "broadcast_cartesian_transform": True}},
    }
    path = tmp / "dual_ekf_navsat.yaml"
    path.write_text(yaml.safe_dump(config))
    return path


def test_gps_keeps_the_map_estimate_on_the_truth(router: str, procs, tmp_path: Path) -> None:
    params = str(_params(tmp_path))
    run = ("run", "robot_localization")
    nodes = [
        procs.diffctl(*run, "ekf_node", "--ros-args", "-r", "__node:=ekf_filter_node_odom", "--params-file", params,
                      "-r", "odometry/filtered:=/odometry/local"),
        procs.diffctl(*run, "ekf_node", "--ros-args", "-r", "__node:=ekf_filter_node_map", "--params-file", params,
                      "-r", "odometry/filtered:=/odometry/global"),
        procs.diffctl(*run, "navsat_transform_node", "--ros-args", "-r", "__node:=navsat_transform",
                      "--params-file", params, "-r", "imu:=/imu", "-r", "gps/fix:=/gps/fix",
                      "-r", "odometry/filtered:=/odometry/global"),
    ]
    d = Driver()
    try:
        for topic, typename in (("/odometry/local", "nav_msgs/msg/Odometry"),
                                ("/odometry/global", "nav_msgs/msg/Odometry"),
                                ("/odometry/gps", "nav_msgs/msg/Odometry"),
                                ("/gps/filtered", "sensor_msgs/msg/NavSatFix")):
            d.watch(topic, typename)
        static = d.node.create_publisher("/tf_static", "tf2_msgs/msg/TFMessage", latched=True)
        static.publish({"transforms": [{"header": {"frame_id": "base_link"}, "child_frame_id": "gps_link",
                                        "transform": {"translation": dict(zip("xyz", ANTENNA, strict=True))}}]})
        rng = np.random.default_rng(3)
        # The fixes' noise has a generator of its own: the anchor fix's error must not depend on the step the
        # fixes start at.
        gps_rng = np.random.default_rng(4)
        odom = d.publisher("/wheel/odometry", "nav_msgs/msg/Odometry", subscribers=2)
        imu = d.publisher("/imu", "sensor_msgs/msg/Imu", subscribers=3)
        gps = d.publisher("/gps/fix", "sensor_msgs/msg/NavSatFix")
        start_ns = d.now_ns
        steps, dt = 500, 0.05  # 25 s at 20 Hz, a fix every 0.2 s
        worst_global = 0.0
        errors = []
        # navsat_transform_node takes the map frame's heading from the latest map estimate when the first fix
        # comes: fixes start once that estimate has the IMU's heading in it (a slow filter may fuse the wheel
        # odometry of a step before its IMU sample, and an estimate without it points 0.3 rad off).
        heading_in = False
        for i in range(steps):
            d.now_ns += int(dt * SEC)
            d.tick()
            t = (d.now_ns - start_ns) / SEC
            x, y, yaw = truth(t)
            moving = t > REST_S
            odom.publish(d.stamped({
                "header": {"frame_id": "odom"}, "child_frame_id": "base_link",
                "twist": {"twist": {"linear": {"x": SPEED * ODOM_SCALE * moving},
                                    "angular": {"z": TURN * ODOM_SCALE * moving}},
                          "covariance": [1e-3 if k in (0, 7, 35) else 0.0 for k in range(36)]}}))
            imu.publish(d.stamped({
                "header": {"frame_id": "base_link"}, "orientation": quat_rpy(0.0, 0.0, yaw),
                "orientation_covariance": [1e-4, 0, 0, 0, 1e-4, 0, 0, 0, 1e-4],
                "angular_velocity": {"z": TURN * moving + rng.normal(0.0, GYRO_SIGMA)},
                "angular_velocity_covariance": [GYRO_SIGMA ** 2 if k in (0, 4, 8) else 0.0 for k in range(9)]}))
            if i % 4 == 0 and heading_in:
                ax = x + math.cos(yaw) * ANTENNA[0] - math.sin(yaw) * ANTENNA[1] + gps_rng.normal(0.0, GPS_SIGMA)
                ay = y + math.sin(yaw) * ANTENNA[0] + math.cos(yaw) * ANTENNA[1] + gps_rng.normal(0.0, GPS_SIGMA)
                lat, lon, alt = pymap3d.enu2geodetic(ax, ay, ANTENNA[2], *DATUM)
                gps.publish(d.stamped({"header": {"frame_id": "gps_link"}, "status": {"status": 0},
                                       "latitude": float(lat), "longitude": float(lon), "altitude": float(alt),
                                       "position_covariance": [GPS_SIGMA ** 2 if k in (0, 4, 8) else 0.0
                                                               for k in range(9)],
                                       "position_covariance_type": 2}))
            if i % 5 == 4:
                d.wait_output("/odometry/local", d.now_ns)
                g = d.wait_output("/odometry/global", d.now_ns)
                heading_in = heading_in or abs(math.remainder(yaw_of(g.pose.pose.orientation) - yaw, math.tau)) < 0.01
                if t > 5.0:  # once the transform is made and a few fixes are in
                    gx, gy, _ = truth((g.header.stamp.sec * SEC + g.header.stamp.nanosec - start_ns) / SEC)
                    err = math.hypot(g.pose.pose.position.x - gx, g.pose.pose.position.y - gy)
                    errors.append((round(t, 2), round(err, 3)))
                    worst_global = max(worst_global, err)
        # Compared at the outputs' own stamps: the clock may have run past the last step while the test waited.
        g, loc = d.latest("/odometry/global"), d.latest("/odometry/local")
        x, y, yaw = truth((types.time_ns(g.header.stamp) - start_ns) / SEC)
        global_err = math.hypot(g.pose.pose.position.x - x, g.pose.pose.position.y - y)
        travelled = math.hypot(loc.pose.pose.position.x, loc.pose.pose.position.y)
        true_travel = math.hypot(*truth((types.time_ns(loc.header.stamp) - start_ns) / SEC)[:2])
        # dead reckoning over-reads by the odometry's 4 % (the IMU fixes its heading, not its length)
        assert travelled == pytest.approx(true_travel * ODOM_SCALE, rel=0.01), (travelled, true_travel)
        # The map frame is anchored on one (noisy) fix, as upstream anchors it: within 3 sigma of the truth, far
        # inside the dead reckoning's drift.
        assert global_err < 3 * GPS_SIGMA * math.sqrt(2), \
            f"map estimate {global_err:.3f} m off the truth at the end: {g.pose.pose.position} vs {(x, y)}; " \
            f"{errors}; samples seen: {d.count}"
        assert worst_global < 0.5, f"map estimate up to {worst_global:.3f} m off the truth: {errors}"
        assert abs(math.remainder(yaw_of(g.pose.pose.orientation) - yaw, math.tau)) < 0.02
        # gps/filtered: the map estimate back on the globe, at the truth's latitude and longitude
        fix = d.wait_output("/gps/filtered", d.now_ns - SEC)
        ft = (fix.header.stamp.sec * SEC + fix.header.stamp.nanosec - start_ns) / SEC
        e, n, _ = pymap3d.geodetic2enu(fix.latitude, fix.longitude, DATUM[2], *DATUM)
        tx, ty, _ = truth(ft)
        assert math.hypot(e - tx, n - ty) < 0.3, (e, n, tx, ty)
        # toLL / fromLL: a map point 10 m east and 5 m north of the start, and back
        to_ll = d.call("/toLL", "robot_localization/srv/ToLL", {"map_point": {"x": 10.0, "y": 5.0}})
        e, n, _ = pymap3d.geodetic2enu(to_ll.ll_point.latitude, to_ll.ll_point.longitude, DATUM[2], *DATUM)
        assert math.hypot(e - 10.0, n - 5.0) < 0.3, (e, n)
        lat, lon, _ = pymap3d.enu2geodetic(10.0, 5.0, 0.0, *DATUM)
        from_ll = d.call("/fromLL", "robot_localization/srv/FromLL",
                         {"ll_point": {"latitude": float(lat), "longitude": float(lon), "altitude": 0.0}})
        assert math.hypot(from_ll.map_point.x - 10.0, from_ll.map_point.y - 5.0) < 0.3, from_ll.map_point
    finally:
        d.close()
        codes = [procs.stop(p) for p in nodes]
    assert codes == [0, 0, 0], [p.stdout.read()[-2000:] for p in nodes]
