"""gpu_lidar / lidar / ray sensors on the CPU: PyBullet `rayTestBatch` per scan, gz.msgs.LaserScan out.

Noise follows SDF/Gazebo: Gaussian with `mean` and `stddev` from the sensor's own seeded numpy Generator.
Intensities are the `<laser_retro>` of the visuals a ray hits, as gz-rendering reports them; PyBullet tells only
the link hit, so a link whose visuals carry different values reports the largest.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pybullet as pb

from diffctl.bus import gz
from diffctl.description.model import Sensor
from diffctl.sim.entity import Entity
from diffctl.sim.sensors.common import frame_id, pose_msg, rotation
from diffctl.sim.sensors.topics import POINTS, SCAN

# gpu_lidar's points: InitPointCloudPacked(aligned, {xyz FLOAT32, intensity FLOAT32, ring UINT16}).
LIDAR_POINT_STEP = 32
_LIDAR_FIELDS = (("x", 0, "FLOAT32"), ("y", 4, "FLOAT32"), ("z", 8, "FLOAT32"), ("intensity", 16, "FLOAT32"))
_LIDAR_DTYPE = np.dtype(
    {
        "names": ["x", "y", "z", "intensity", "ring"],
        "formats": ["<f4", "<f4", "<f4", "<f4", "<u2"],
        "offsets": [0, 4, 8, 16, 24],
        "itemsize": LIDAR_POINT_STEP,
    }
)
# Rays per rayTestBatch: PyBullet refuses more than 16,384 (SharedMemoryPublic.h) and answers a batch of exactly
# 16,384 with one result short; a denser scan is cast in batches of this many.
RAYS_PER_BATCH = 16383


def lidar_directions(
    h_samples: int, h_min: float, h_max: float, v_samples: int, v_min: float, v_max: float
) -> np.ndarray:
    """Unit ray directions in the sensor frame, horizontal index fastest (Gazebo's range order), shape (n, 3)."""
    h = np.linspace(h_min, h_max, h_samples) if h_samples > 1 else np.array([h_min])
    v = np.linspace(v_min, v_max, v_samples) if v_samples > 1 else np.array([v_min])
    vv, hh = np.meshgrid(v, h, indexing="ij")
    return np.stack([np.cos(vv) * np.cos(hh), np.cos(vv) * np.sin(hh), np.sin(vv)], axis=-1).reshape(-1, 3)


def ranges_from_hits(fractions: np.ndarray, hit: np.ndarray, range_min_m: float, range_max_m: float) -> np.ndarray:
    """Ranges of rays cast from range_min to range_max: +inf where nothing was hit (as Gazebo reports)."""
    r = range_min_m + fractions * (range_max_m - range_min_m)
    return np.where(hit, r, np.inf)


def lidar_points(ranges: np.ndarray, directions: np.ndarray) -> np.ndarray:
    """Points (n, 3) float32 in the sensor frame: range times the ray's unit direction, in float32 as Gazebo
    computes them (so a ray that hit nothing gives ±inf, or NaN where the direction's component is 0)."""
    with np.errstate(invalid="ignore"):
        return np.asarray(ranges, dtype=np.float32)[:, None] * directions


def pack_lidar_points(points: np.ndarray, h_samples: int, intensities: np.ndarray | None = None) -> bytes:
    """PointCloudPacked data: x, y, z, intensity (the hit visual's laser_retro, else 0), ring = vertical row."""
    out = np.zeros(len(points), dtype=_LIDAR_DTYPE)
    out["x"], out["y"], out["z"] = points[:, 0], points[:, 1], points[:, 2]
    if intensities is not None:
        out["intensity"] = intensities
    out["ring"] = np.arange(len(points)) // h_samples
    return out.tobytes()


def lidar_cloud_msg(sim_time_ns: int, frame: str, h_samples: int, v_samples: int, data: bytes) -> dict:
    fields = [{"name": n, "offset": o, "datatype": t, "count": 1} for n, o, t in _LIDAR_FIELDS]
    points = np.frombuffer(data, dtype=_LIDAR_DTYPE)
    finite = np.isfinite(points["x"]) & np.isfinite(points["y"]) & np.isfinite(points["z"])
    return {
        "header": gz.header(sim_time_ns, frame),
        "field": [*fields, {"name": "ring", "offset": 24, "datatype": "UINT16", "count": 1}],
        "height": v_samples,
        "width": h_samples,
        "is_bigendian": False,
        "point_step": LIDAR_POINT_STEP,
        "row_step": LIDAR_POINT_STEP * h_samples,
        "data": data,
        # gpu_lidar clears is_dense when any range is inf or NaN (GpuLidarSensor FillPointCloudMsg).
        "is_dense": bool(finite.all()),
    }


class Lidar:
    """gpu_lidar / lidar / ray sensors. Rays start at range_min so the sensor never sees its own housing."""

    def __init__(
        self,
        entity: Entity,
        sensor: Sensor,
        rng: np.random.Generator,
        retro: Callable[[], dict[tuple[int, int], float]] | None = None,
    ) -> None:
        spec = sensor.lidar
        assert spec is not None
        self.entity, self.sensor, self.spec, self.rng = entity, sensor, spec, rng
        # (PyBullet body, link) → laser_retro of the world's visuals there; empty: every intensity is 0
        self._retro = retro or (lambda: {})
        self.intensities = np.zeros(0, dtype=np.float64)  # of the latest scan, one per range
        self.frame_id = frame_id(entity.name, sensor)
        self.count = spec.horizontal_samples * spec.vertical_samples
        self.body, self.link, offset = entity.link_frame(sensor.link)
        # rayTestBatch takes rays relative to a link in that link's centre-of-mass frame.
        inertial = entity.inertial_frame(self.body, self.link)
        in_com = inertial.inverse().compose(offset).compose(sensor.pose_link)
        d = lidar_directions(
            spec.horizontal_samples,
            spec.horizontal_min_angle_rad,
            spec.horizontal_max_angle_rad,
            spec.vertical_samples,
            spec.vertical_min_angle_rad,
            spec.vertical_max_angle_rad,
        )
        self.directions = d.astype(np.float32)  # in the sensor frame, for the point cloud
        rot = np.array(rotation(in_com))
        origin = np.array(in_com.xyz)
        world_dirs = d @ rot.T
        self._from = (origin + world_dirs * spec.range_min_m).tolist()
        self._to = (origin + world_dirs * spec.range_max_m).tolist()
        self._noise = spec.noise if spec.noise.active else None
        self._step = spec.angle_increment_rad
        v_n = spec.vertical_samples
        self._v_step = (spec.vertical_max_angle_rad - spec.vertical_min_angle_rad) / (v_n - 1) if v_n > 1 else 0.0

    def scan(self) -> np.ndarray:
        """Ranges in metres (with noise when the SDF asks for it), +inf where nothing is within range."""
        if self.count <= RAYS_PER_BATCH:
            res = self._cast(0, self.count)
        else:
            n = RAYS_PER_BATCH
            res = [r for start in range(0, self.count, n) for r in self._cast(start, start + n)]
        # One pass over the result tuples: a miss has fraction 1 and object -1; mark it with fraction 2.
        frac = np.fromiter((r[2] if r[0] >= 0 else 2.0 for r in res), dtype=np.float64, count=self.count)
        retro = self._retro()
        if retro:
            # as gz-rendering's GpuRays: the hit visual's laser_retro, 0 on a miss or a visual without one
            self.intensities = np.fromiter(
                (retro.get((r[0], r[1]), 0.0) if r[0] >= 0 else 0.0 for r in res), dtype=np.float64, count=self.count
            )
        else:
            self.intensities = np.zeros(self.count, dtype=np.float64)
        ranges = ranges_from_hits(frac, frac < 1.5, self.spec.range_min_m, self.spec.range_max_m)
        if self._noise is not None:
            n = self._noise
            ranges = ranges + self.rng.normal(n.mean, n.stddev, self.count) if n.stddev > 0 else ranges + n.mean
            ranges = np.clip(ranges, self.spec.range_min_m, None)
        return ranges

    def _cast(self, start: int, end: int) -> tuple:
        return pb.rayTestBatch(
            self._from[start:end],
            self._to[start:end],
            parentObjectUniqueId=self.body,
            parentLinkIndex=self.link,
            physicsClientId=self.entity.client,
        )

    def sample(self, sim_time_ns: int) -> dict:
        return self.scan_msg(sim_time_ns, self.scan())

    def messages(self, sim_time_ns: int, wanted: set[str]) -> dict[str, dict]:
        """The `wanted` outputs ("scan", "points") from one scan, as gpu_lidar publishes T and T/points."""
        if not wanted:
            return {}
        ranges = self.scan()
        out = {}
        if SCAN in wanted:
            out[SCAN] = self.scan_msg(sim_time_ns, ranges)
        if POINTS in wanted:
            s = self.spec
            points = lidar_points(ranges, self.directions)
            data = pack_lidar_points(points, s.horizontal_samples, self._intensities_for(ranges))
            out[POINTS] = lidar_cloud_msg(sim_time_ns, self.frame_id, s.horizontal_samples, s.vertical_samples, data)
        return out

    def _intensities_for(self, ranges: np.ndarray) -> np.ndarray:
        # the latest scan's, when `ranges` came from it
        n = np.size(ranges)
        return self.intensities if np.size(self.intensities) == n else np.zeros(n, dtype=np.float64)

    def scan_msg(self, sim_time_ns: int, ranges: np.ndarray) -> dict:
        s = self.spec
        pose = self.entity.link_pose(self.sensor.link).compose(self.sensor.pose_link)
        return {
            "header": gz.header(sim_time_ns, self.frame_id),
            "frame": self.frame_id,
            "world_pose": pose_msg(pose),
            "angle_min": s.horizontal_min_angle_rad,
            "angle_max": s.horizontal_max_angle_rad,
            "angle_step": self._step,
            "range_min": s.range_min_m,
            "range_max": s.range_max_m,
            "count": s.horizontal_samples,
            "vertical_angle_min": s.vertical_min_angle_rad,
            "vertical_angle_max": s.vertical_max_angle_rad,
            "vertical_angle_step": self._v_step,
            "vertical_count": s.vertical_samples,
            # As gz-sensors sends them (full doubles); the gz encoding carries the array as raw bytes.
            "ranges": np.ascontiguousarray(ranges, dtype=np.float64),
            # gz-sensors fills one intensity per range: the laser_retro of the hit visual, 0 without any
            "intensities": self._intensities_for(ranges),
        }
