"""What the page shows, kept up to date from bus messages and turned into JSON views for a fixed frame.

Callbacks from bus threads write under one lock and bump a version per stream; the server reads views at
its own pace and sends a stream to a browser only when its version moved. No bus or asyncio here, so the
whole scene is testable with plain message objects.
"""

from __future__ import annotations

import math
import threading
import time
from collections import deque
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from diffctl.errors import DiffctlError
from diffctl.viz.rates import RateMeter, RtfMeter
from diffctl.viz.robot_model import RobotModel, parse_description
from diffctl.viz.rviz_config import RvizConfig
from diffctl.viz.settings import VizSettings
from diffctl.viz.transforms import IDENTITY as IDENTITY_TF
from diffctl.viz.transforms import TfBuffer, Transform, strip_frame

STREAMS = ("robot", "frame", "scan", "paths", "status", "graph", "image")
POSITION_TOLERANCE_M = 0.05  # RViz Odometry's defaults for when a new arrow joins the trail
ANGLE_TOLERANCE_RAD = 0.1


def _r(v: float | None, nd: int = 4) -> float | None:
    """Rounded for a compact JSON; None (JSON null, shown as "—") for missing or non-finite values."""
    return round(float(v), nd) if v is not None and math.isfinite(v) else None


def _number(v: Any) -> float | None:
    return float(v) if isinstance(v, int | float) and not isinstance(v, bool) else None


def _seconds(t: Any) -> float | None:
    """A gz.msgs.Time {"sec", "nsec"} (or plain seconds) in seconds."""
    if isinstance(t, dict):
        return int(t.get("sec", 0)) + int(t.get("nsec", 0)) * 1e-9
    return _number(t)


def _tf_of(translation: Any, rotation: Any) -> Transform:
    return Transform(
        (float(translation.x), float(translation.y), float(translation.z)),
        (float(rotation.x), float(rotation.y), float(rotation.z), float(rotation.w)),
    )


def _rgba_css(rgba: tuple[float, float, float, float]) -> str:
    r, g, b, a = (max(0.0, min(1.0, c)) for c in rgba)
    return f"rgba({round(r * 255)},{round(g * 255)},{round(b * 255)},{a:.2f})"


@dataclass
class _Odom:
    frame_id: str = ""
    child_frame_id: str = ""
    pose: Transform | None = None
    linear_mps: float = 0.0
    angular_radps: float = 0.0
    trail: deque[tuple[float, float, float]] = field(default_factory=lambda: deque(maxlen=100))


@dataclass
class _Robot:
    """One RobotModel display's robot: its model once its description arrived, and its TF prefix."""

    prefix: str
    model: RobotModel | None = None
    error: str | None = None

    def frame(self, link: str) -> str:
        return f"{self.prefix}/{link}" if self.prefix else link


@dataclass
class _Scan:
    frame_id: str  # as the message says
    anchor: str  # the frame `points_m` are expressed in: the TF root when the scan arrived
    points_m: np.ndarray  # (3, n)


def _apply(tf: Transform, points_m: np.ndarray) -> np.ndarray:
    return np.array(tf.rotation_matrix()) @ points_m + np.array(tf.translation_m)[:, None]


class Scene:
    def __init__(self, config: RvizConfig, settings: VizSettings) -> None:
        self.config = config
        self.settings = settings
        self._lock = threading.Lock()
        self.versions = dict.fromkeys(STREAMS, 0)
        self.tf = TfBuffer()
        self.robot: RobotModel | None = None  # the first display's robot (the one a single-robot page shows)
        self.robot_error: str | None = None
        # Per description topic; several robots (a fleet) are several RobotModel displays with TF prefixes.
        self._robots: dict[str, _Robot] = {t: _Robot(prefix) for t, prefix in config.robot_models()}
        self._gt_models: dict[str, Transform] = {}  # ground truth per simulated model name
        self._odom: dict[str, _Odom] = {}
        self._keep = {d.topic: d.keep for d in config.displays if d.kind == "odometry" and d.topic}
        self._scans: dict[str, _Scan] = {}
        self._gt: Transform | None = None
        self._joints: dict[str, tuple[float | None, float | None, float | None]] = {}
        self.rates = RateMeter()
        self._rtf = RtfMeter()
        self._stats: dict[str, Any] = {}
        self._stats_wall_s = 0.0
        self._topics: list[dict[str, Any]] = []
        self._controllers: list[dict[str, Any]] | None = None
        self._images: dict[str, Any] = {}
        self.time_jumps = 0

    def _bump(self, *streams: str) -> None:
        for s in streams:
            self.versions[s] += 1

    # ---- inputs (bus threads) ------------------------------------------------------------------------

    def count(self, topic: str) -> None:
        with self._lock:
            self.rates.record(topic, time.monotonic())

    def set_robot_description(self, sdf_text: str, topic: str | None = None) -> None:
        try:
            robot, error = parse_description(sdf_text), None
        except DiffctlError as e:
            robot, error = None, str(e)
        except Exception as e:  # a loader bug must not take the visualizer down with it
            robot, error = None, f"cannot read the robot description: {type(e).__name__}: {e}"
        with self._lock:
            topic = topic if topic is not None else next(iter(self._robots), "/robot_description")
            entry = self._robots.setdefault(topic, _Robot(""))
            entry.model, entry.error = robot, error
            if topic == next(iter(self._robots)):
                self.robot, self.robot_error = robot, error
            self._bump("robot", "frame")

    def on_tf(self, msg: Any, static: bool = False) -> None:
        with self._lock:
            for t in msg.transforms:
                tf = _tf_of(t.transform.translation, t.transform.rotation)
                self.tf.set(t.header.frame_id, t.child_frame_id, tf, static=static)
            self._bump("frame", "paths", "scan")

    def on_odometry(self, topic: str, msg: Any) -> None:
        p = msg.pose.pose
        pose = _tf_of(p.position, p.orientation)
        if not pose.is_finite():
            return
        with self._lock:
            od = self._odom.get(topic)
            if od is None:
                od = self._odom[topic] = _Odom(trail=deque(maxlen=max(1, self._keep.get(topic, 100))))
            od.frame_id, od.child_frame_id = strip_frame(msg.header.frame_id), strip_frame(msg.child_frame_id)
            od.pose = pose
            od.linear_mps = float(msg.twist.twist.linear.x)
            od.angular_radps = float(msg.twist.twist.angular.z)
            x, y, yaw = pose.translation_m[0], pose.translation_m[1], pose.yaw_rad
            if (
                not od.trail
                or math.hypot(x - od.trail[-1][0], y - od.trail[-1][1]) >= POSITION_TOLERANCE_M
                or abs(math.remainder(yaw - od.trail[-1][2], 2 * math.pi)) >= ANGLE_TOLERANCE_RAD
            ):
                od.trail.append((x, y, yaw))
                self._bump("paths")
            self._bump("frame", "status")

    def on_ground_truth(self, fields: dict[str, Any], model: str | None = None) -> None:
        """gz.msgs.Pose_V from the simulator: the model's true pose in the world (Gazebo's GUI shows this).
        `model` names the simulated model (default: the settings' ground_truth_model)."""
        model = model or self.settings.ground_truth_model
        poses = fields.get("pose") or []
        entry = next((p for p in poses if p.get("name") == model), None)
        if entry is None and poses:
            entry = poses[0]
        if entry is None:
            return
        pos, q = entry.get("position") or {}, entry.get("orientation") or {}
        tf = Transform(
            (float(pos.get("x", 0)), float(pos.get("y", 0)), float(pos.get("z", 0))),
            (float(q.get("x", 0)), float(q.get("y", 0)), float(q.get("z", 0)), float(q.get("w", 1))),
        )
        if tf.is_finite():
            with self._lock:
                self._gt_models[model] = tf
                if model == self.settings.ground_truth_model:
                    self._gt = tf
                self._bump("frame", "paths", "scan")

    def on_scan(self, topic: str, msg: Any) -> None:
        ranges = np.asarray(msg.ranges, dtype=np.float64)
        angles = float(msg.angle_min) + float(msg.angle_increment) * np.arange(len(ranges))
        ok = np.isfinite(ranges) & (ranges >= float(msg.range_min)) & (ranges <= float(msg.range_max))
        r, a = ranges[ok], angles[ok]
        pts = np.stack([r * np.cos(a), r * np.sin(a), np.zeros_like(r)])
        frame = strip_frame(msg.header.frame_id)
        with self._lock:
            # Placed with the TF of its arrival, as RViz does: walls stay put while the robot moves between
            # scans, instead of riding along with the newest transform.
            root, pose = self.tf.root_pose(frame)
            self._scans[topic] = _Scan(frame, root, _apply(pose, pts))
            self._bump("scan")

    def on_joint_states(self, msg: Any) -> None:
        def at(seq: Any, i: int) -> float | None:
            return float(seq[i]) if seq is not None and i < len(seq) else None

        with self._lock:
            for i, name in enumerate(msg.name):
                self._joints[name] = (at(msg.position, i), at(msg.velocity, i), at(msg.effort, i))
            self._bump("status")

    def on_clock(self, sim_s: float, wall_s: float | None = None) -> None:
        with self._lock:
            if self._rtf.record(sim_s, time.monotonic() if wall_s is None else wall_s):
                # RViz resets on a jump back in time: old TF and trails belong to a run that no longer exists.
                self.time_jumps += 1
                self.tf.clear_dynamic()
                for od in self._odom.values():
                    od.trail.clear()
                self._bump("frame", "paths", "scan")
            self._bump("status")

    def on_stats(self, fields: dict[str, Any]) -> None:
        with self._lock:
            self._stats = dict(fields)
            self._stats_wall_s = time.monotonic()
            self._bump("status")

    def on_image(self, topic: str, msg: Any) -> None:
        with self._lock:
            self._images[topic] = msg
            self._bump("image")

    def set_topics(self, topics: list[dict[str, Any]]) -> None:
        with self._lock:
            self._topics = topics
            self._bump("graph")

    def set_controllers(self, controllers: list[dict[str, Any]] | None) -> None:
        with self._lock:
            self._controllers = controllers
            self._bump("graph")

    # ---- views (server thread) -----------------------------------------------------------------------

    def robot_view(self) -> dict[str, Any]:
        with self._lock:
            r = self.robot
            return {
                "type": "robot",
                "name": r.name if r else None,
                "links": r.links if r else [],
                "skipped": list(r.skipped) if r else [],
                "joints": [{"name": n, "lower": lo, "upper": hi} for n, lo, hi in r.movable] if r else [],
                "error": self.robot_error,
                "robots": [
                    {"topic": t, "prefix": e.prefix, "name": e.model.name if e.model else None, "error": e.error}
                    for t, e in self._robots.items()
                ],
            }

    def _in_fixed(self, fixed: str) -> dict[str, Transform]:
        """Every frame's pose in `fixed`: TF's, plus the trees of prefixed robots that TF does not connect to
        `fixed`, placed by the simulator's ground truth of the model named like the prefix (each robot of a
        fleet has its own odom, and nothing in TF says where one odom is relative to another)."""
        known = self.tf.all_in(fixed)
        world = IDENTITY_TF if fixed == "world" else known.get("world")
        if world is None:
            return known
        for entry in self._robots.values():
            gt = self._gt_models.get(entry.prefix) if entry.prefix else None
            if gt is None or entry.model is None:
                continue
            link = next((a for a in entry.model.anchors if entry.frame(a) in self.tf.frames()), None)
            if link is None or entry.frame(link) in known:
                continue
            root, link_in_root = self.tf.root_pose(entry.frame(link))
            root_in_fixed = world.compose(gt).compose(entry.model.anchors[link]).compose(link_in_root.inverse())
            for frame, pose in self.tf.all_in(root).items():
                known.setdefault(frame, root_in_fixed.compose(pose))
        return known

    def frame_view(self, fixed: str) -> dict[str, Any]:
        with self._lock:
            known = self._in_fixed(fixed)
            frames = {
                name: [_r(t.translation_m[0]), _r(t.translation_m[1]), _r(t.translation_m[2]), _r(t.yaw_rad)]
                for name, t in known.items()
            }
            robot = []
            for entry in self._robots.values():
                if entry.model is None:
                    continue
                mine = known
                if entry.prefix:
                    head = entry.prefix + "/"
                    mine = {f[len(head):]: t for f, t in known.items() if f.startswith(head)}
                for shape, o in entry.model.outlines(mine):
                    pts = [_r(c) for p in o.points_xy_m for c in p]
                    robot.append({"link": entry.frame(shape.link), "pts": pts, "color": _rgba_css(shape.rgba)})
            odom = []
            for topic, od in self._odom.items():
                entry: dict[str, Any] = {
                    "topic": topic,
                    "frame": od.frame_id,
                    "child": od.child_frame_id,
                    "v": _r(od.linear_mps),
                    "w": _r(od.angular_radps),
                    "pose": None,
                }
                to_fixed = known.get(od.frame_id) if od.frame_id else None
                if od.pose is not None and to_fixed is not None:
                    p = to_fixed.compose(od.pose)
                    entry["pose"] = [_r(p.translation_m[0]), _r(p.translation_m[1]), _r(p.yaw_rad)]
                odom.append(entry)
            gt = None
            gt_in_fixed = self._ground_truth_in(fixed)
            if gt_in_fixed is not None:
                gt = [_r(gt_in_fixed.translation_m[0]), _r(gt_in_fixed.translation_m[1]), _r(gt_in_fixed.yaw_rad)]
            return {
                "type": "frame",
                "fixed": fixed,
                # RViz's "Fixed Frame [map] does not exist" once TF has frames, none of them this one.
                "fixed_known": fixed in self.tf.frames() or not self.tf.frames() or len(known) > 1,
                "frames": frames,
                "robot": robot,
                "odom": odom,
                "gt": gt,
                "parents": self.tf.parents(),
            }

    def _ground_truth_in(self, fixed: str) -> Transform | None:
        """The simulator's world pose of the robot in `fixed`: through a TF frame named 'world' when there is
        one, else only in a root frame (odom, map), whose origin is the world's for a robot spawned there."""
        if self._gt is None:
            return None
        world = self.tf.lookup(fixed, "world") if "world" in self.tf.frames() else None
        if world is not None:
            return world.compose(self._gt)
        return self._gt if fixed not in self.tf.parents() else None

    def paths_view(self, fixed: str) -> dict[str, Any]:
        with self._lock:
            paths = {}
            known = self._in_fixed(fixed)
            for topic, od in self._odom.items():
                to_fixed = known.get(od.frame_id) if od.frame_id else None
                if to_fixed is None:
                    continue
                pts: list[float] = []
                for x, y, yaw in od.trail:
                    p = to_fixed.apply((x, y, 0.0))
                    pts += [_r(p[0], 3), _r(p[1], 3), _r(yaw + to_fixed.yaw_rad, 3)]
                paths[topic] = pts
            return {"type": "paths", "fixed": fixed, "paths": paths}

    def scan_view(self, fixed: str) -> dict[str, Any]:
        with self._lock:
            scans = {}
            known = self._in_fixed(fixed)
            for topic, s in self._scans.items():
                to_fixed = known.get(s.anchor)
                if to_fixed is None:
                    scans[topic] = {"frame": s.frame_id, "pts": [], "ok": False}
                    continue
                xyz = _apply(to_fixed, s.points_m)
                pts = np.round(xyz[:2].T.ravel(), 3).tolist()
                scans[topic] = {"frame": s.frame_id, "pts": pts, "ok": True}
            return {"type": "scan", "fixed": fixed, "scans": scans}

    def status_view(self) -> dict[str, Any]:
        now = time.monotonic()
        with self._lock:
            rtf, source = self._rtf.rtf(now), "clock"
            stats = self._stats if self._stats and now - self._stats_wall_s < 3.0 else None
            sim_s = self._rtf.sim_s
            if stats is not None:
                # The simulator's own figure beats one derived from /clock (which the bridge may throttle).
                if _number(stats.get("real_time_factor")) is not None:
                    rtf, source = _number(stats["real_time_factor"]), "sim stats"
                if sim_s is None:
                    sim_s = _seconds(stats.get("sim_time"))
            joints = [
                {"name": n, "position": _r(p), "velocity": _r(v), "effort": _r(e)}
                for n, (p, v, e) in sorted(self._joints.items())
            ]
            sim_info = None
            if stats is not None:
                sim_info = {
                    k: stats.get(k)
                    for k in ("paused", "iterations", "step_time_us", "model_count")
                    if k in stats
                }
            return {
                "type": "status",
                "sim_time": _r(sim_s, 3),
                "rtf": _r(rtf, 3),
                "rtf_source": source if rtf is not None else None,
                "sim": sim_info,
                "joints": joints,
                "time_jumps": self.time_jumps,
            }

    def graph_view(self) -> dict[str, Any]:
        now = time.monotonic()
        with self._lock:
            topics = []
            for t in self._topics:
                hz = self.rates.rate_hz(t["name"], now)
                topics.append({**t, "hz": None if hz is None else _r(hz, 1)})
            return {
                "type": "graph",
                "topics": topics,
                "controllers": self._controllers,
                "frames": self.tf.frames(),
            }

    def latest_image(self, topic: str) -> Any:
        with self._lock:
            return self._images.get(topic)
