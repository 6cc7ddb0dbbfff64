"""What a failed launch test leaves for a person to look at (`--artifacts DIR`): each process's log, an MCAP
bag of the run (diffctl's `bag record`), and a PNG of the scene at the moment the first test failed.

The scene is watched on the test's own bus while the launch runs (TF, the robot's trail, the latest laser
scan), frozen when a test fails, and drawn top-down with Pillow: a grid in metres, the trail, every TF frame
as a pair of axes, the robot's footprint, the scan's points.
"""

from __future__ import annotations

import contextlib
import math
import os
import shutil
import signal
import subprocess
import sys
import threading
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from diffctl.viz.transforms import TfBuffer, Transform

BASE_FRAMES = ("base_footprint", "base_link")
TRAIL_MIN_STEP_M = 0.01


@dataclass
class Snapshot:
    frames: dict[str, Transform] = field(default_factory=dict)  # pose of each frame in the fixed frame
    fixed_frame: str = ""
    trail: list[tuple[float, float]] = field(default_factory=list)
    scan_xy: list[tuple[float, float]] = field(default_factory=list)
    base: Transform | None = None
    what: str = ""


class SceneWatcher:
    """TF, trail and scan of the run, from a node of its own (rclpy API) spun on a thread."""

    def __init__(self) -> None:
        import rclpy
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
        from sensor_msgs.msg import LaserScan
        from tf2_msgs.msg import TFMessage

        self._lock = threading.Lock()
        self.tf = TfBuffer()
        self.trail: list[tuple[float, float]] = []
        self.scan: Any = None
        self.frozen: Snapshot | None = None
        self._context = rclpy.Context()
        rclpy.init(context=self._context)
        self._node = rclpy.create_node("_launch_test_scene", context=self._context)
        static = QoSProfile(depth=100, durability=DurabilityPolicy.TRANSIENT_LOCAL)
        sensor = QoSProfile(depth=5, reliability=ReliabilityPolicy.BEST_EFFORT)
        self._node.create_subscription(TFMessage, "/tf", lambda m: self._on_tf(m, False), 100)
        self._node.create_subscription(TFMessage, "/tf_static", lambda m: self._on_tf(m, True), static)
        self._node.create_subscription(LaserScan, "/scan", self._on_scan, sensor)
        self._executor = SingleThreadedExecutor(context=self._context)
        self._executor.add_node(self._node)
        self._running = True
        self._thread = threading.Thread(target=self._spin, name="scene_watcher", daemon=True)
        self._thread.start()

    def _spin(self) -> None:
        while self._running:
            try:
                self._executor.spin_once(timeout_sec=0.1)
            except Exception:
                return

    def _on_tf(self, msg: Any, static: bool) -> None:
        with self._lock:
            for t in msg.transforms:
                tr, q = t.transform.translation, t.transform.rotation
                self.tf.set(t.header.frame_id, t.child_frame_id,
                            Transform((tr.x, tr.y, tr.z), (q.x, q.y, q.z, q.w)), static=static)
            base = self._base()
            if base is not None:
                x, y = base[1].translation_m[0], base[1].translation_m[1]
                if not self.trail or math.dist(self.trail[-1], (x, y)) >= TRAIL_MIN_STEP_M:
                    self.trail.append((x, y))

    def _on_scan(self, msg: Any) -> None:
        with self._lock:
            self.scan = msg

    def _base(self) -> tuple[str, Transform] | None:
        frames = set(self.tf.frames())
        for name in BASE_FRAMES:
            if name in frames:
                root, pose = self.tf.root_pose(name)
                return root, pose
        return None

    def snapshot(self, what: str = "") -> Snapshot:
        with self._lock:
            base = self._base()
            fixed = base[0] if base else (self.tf.frames()[0] if self.tf.frames() else "")
            snap = Snapshot(frames=self.tf.all_in(fixed) if fixed else {}, fixed_frame=fixed,
                            trail=list(self.trail), base=base[1] if base else None, what=what)
            scan = self.scan
            if scan is not None and fixed:
                pose = self.tf.lookup(fixed, scan.header.frame_id)
                if pose is not None:
                    for i, r in enumerate(scan.ranges):
                        if math.isfinite(r) and scan.range_min <= r <= scan.range_max:
                            a = scan.angle_min + i * scan.angle_increment
                            p = pose.apply((r * math.cos(a), r * math.sin(a), 0.0))
                            snap.scan_xy.append((p[0], p[1]))
            return snap

    def freeze(self, what: str) -> None:
        """The moment of the first failure: the picture shows this."""
        if self.frozen is None:
            self.frozen = self.snapshot(what)

    def close(self) -> None:
        import rclpy

        self._running = False
        self._thread.join(2.0)
        with contextlib.suppress(Exception):
            self._node.destroy_node()
            rclpy.shutdown(context=self._context)


def render_png(snap: Snapshot, path: Path, size_px: int = 800) -> None:
    """A top-down picture of the scene: grid (0.5 m), trail, TF axes, robot footprint, scan points."""
    from PIL import Image, ImageDraw

    xs = [p[0] for p in snap.trail] + [t.translation_m[0] for t in snap.frames.values()]
    ys = [p[1] for p in snap.trail] + [t.translation_m[1] for t in snap.frames.values()]
    near_scan = [p for p in snap.scan_xy if not xs or min(abs(p[0] - xs[-1]), abs(p[1] - ys[-1])) < 5.0]
    xs += [p[0] for p in near_scan]
    ys += [p[1] for p in near_scan]
    if not xs:
        xs, ys = [0.0], [0.0]
    cx, cy = (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2
    span = max(max(xs) - min(xs), max(ys) - min(ys), 1.0) * 1.2 + 0.5
    scale = size_px / span

    def px(x: float, y: float) -> tuple[float, float]:
        return size_px / 2 + (x - cx) * scale, size_px / 2 - (y - cy) * scale

    img = Image.new("RGB", (size_px, size_px), (250, 250, 250))
    d = ImageDraw.Draw(img)
    step = 0.5
    g = math.floor((cx - span / 2) / step) * step
    while g <= cx + span / 2:
        d.line([px(g, cy - span), px(g, cy + span)], fill=(225, 225, 225))
        g += step
    g = math.floor((cy - span / 2) / step) * step
    while g <= cy + span / 2:
        d.line([px(cx - span, g), px(cx + span, g)], fill=(225, 225, 225))
        g += step
    if len(snap.trail) > 1:
        d.line([px(*p) for p in snap.trail], fill=(40, 110, 220), width=3)
    for x, y in snap.scan_xy:
        u, v = px(x, y)
        d.ellipse([u - 1.5, v - 1.5, u + 1.5, v + 1.5], fill=(220, 40, 40))
    axis_m = 0.1
    for _name, pose in sorted(snap.frames.items()):
        ox, oy = pose.translation_m[0], pose.translation_m[1]
        yaw = pose.yaw_rad
        d.line([px(ox, oy), px(ox + axis_m * math.cos(yaw), oy + axis_m * math.sin(yaw))], fill=(230, 0, 0), width=2)
        d.line([px(ox, oy), px(ox - axis_m * math.sin(yaw), oy + axis_m * math.cos(yaw))], fill=(0, 170, 0), width=2)
    if snap.base is not None:
        bx, by, yaw = snap.base.translation_m[0], snap.base.translation_m[1], snap.base.yaw_rad
        half_l, half_w = 0.2, 0.15
        corners = [(half_l, half_w), (-half_l, half_w), (-half_l, -half_w), (half_l, -half_w)]
        pts = [px(bx + a * math.cos(yaw) - b * math.sin(yaw), by + a * math.sin(yaw) + b * math.cos(yaw))
               for a, b in corners]
        d.polygon(pts, outline=(20, 20, 20), width=3)
        d.line([px(bx, by), px(bx + half_l * math.cos(yaw), by + half_l * math.sin(yaw))], fill=(20, 20, 20), width=3)
        d.text((10, 24), f"robot at x={bx:.3f} m y={by:.3f} m yaw={math.degrees(yaw):.1f} deg "
               f"in {snap.fixed_frame}", fill=(0, 0, 0))
    d.text((10, 8), (snap.what or "scene")[:110], fill=(0, 0, 0))
    d.text((10, size_px - 20), f"grid {step} m; trail {len(snap.trail)} points; {len(snap.frames)} TF frames; "
           f"{len(snap.scan_xy)} scan points", fill=(0, 0, 0))
    path.parent.mkdir(parents=True, exist_ok=True)
    img.save(path, format="PNG")


class BagRecorder:
    """`diffctl bag record -a` of the run, beside the launch (not one of its processes), on the test's bus.

    The launch starts only once the recorder says it records: under load its start (an interpreter, the
    client) can outlast a short test, and the bag then held none of the run."""

    READY = "Recording to "

    def __init__(self, folder: Path, ready_timeout_s: float = 60.0) -> None:
        self.folder = folder
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "diffctl", "bag", "record", "-a", "--exclude-regex", "^/camera/",
             "-o", str(folder)],
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, stdin=subprocess.DEVNULL,
            start_new_session=True, env=dict(os.environ),
        )
        self._err: list[str] = []
        self._ready = threading.Event()
        self._reader = threading.Thread(target=self._read, name="bag-record-stderr", daemon=True)
        self._reader.start()
        # a bound for a recorder that never says so (it failed: its errors are kept for the artifacts)
        self._ready.wait(ready_timeout_s)

    def _read(self) -> None:
        assert self.proc.stderr is not None
        for raw in self.proc.stderr:
            line = raw.decode(errors="replace")
            self._err.append(line)
            if self.READY in line:
                self._ready.set()
        self._ready.set()  # ended: nothing to wait for

    def stop(self) -> str:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(self.proc.pid, signal.SIGINT)
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(self.proc.pid, signal.SIGKILL)
            self.proc.wait()
        self._reader.join(timeout=10)
        return "".join(self._err)


class Artifacts:
    """One run's artifacts: started before the launch, kept in `target` only when the run failed."""

    def __init__(self, target: Path, work: Path) -> None:
        self.target = target
        self.work = work
        self.bag = BagRecorder(work / "bag")
        self.scene: SceneWatcher | None = None
        try:
            self.scene = SceneWatcher()
        except Exception as e:
            print(f"[launch_test] no scene picture: {e}", file=sys.stderr)

    def on_failure(self, what: str) -> None:
        if self.scene is not None:
            self.scene.freeze(what)

    def finish(self, failed: bool, logs: dict[str, str]) -> None:
        bag_errors = self.bag.stop()
        snap = None
        if self.scene is not None:
            snap = self.scene.frozen or self.scene.snapshot("the end of the run")
            self.scene.close()
        if not failed:
            shutil.rmtree(self.work, ignore_errors=True)
            return
        self.target.mkdir(parents=True, exist_ok=True)
        for name, text in logs.items():
            (self.target / "logs").mkdir(exist_ok=True)
            (self.target / "logs" / name).write_text(text)
        if (self.work / "bag").is_dir():
            shutil.move(str(self.work / "bag"), str(self.target / "bag"))
        elif bag_errors.strip():
            (self.target / "bag-record-errors.txt").write_text(bag_errors)
        if snap is not None:
            render_png(snap, self.target / "scene.png")
        shutil.rmtree(self.work, ignore_errors=True)
