"""The loaded SDF world and models as frozen dataclasses, every pose already resolved.

`sdf_loader` builds these; the simulator, robot_state_publisher and the controller manager consume them and
never redo frame math. Conventions:
- `pose_world`: the element's frame in the world frame (for a standalone model file: in the frame the model's
  own `<pose>` is given in, i.e. the world it will be spawned into at the identity).
- `pose_model`: the same frame in the (top-level) model frame; `pose_link`: in the owning link's frame.
- Nested models are flattened: their links, joints and frames carry scoped names `outer::inner::link`.
- Sizes are metres, angles radians, masses kilograms, rates hertz.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from dataclasses import dataclass, field

from diffctl.description.pose import Pose, Vec3

# --- geometry -----------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Box:
    size_m: Vec3


@dataclass(frozen=True)
class Cylinder:
    """Axis along the shape's local z (as in SDF and Bullet)."""

    radius_m: float
    length_m: float


@dataclass(frozen=True)
class Sphere:
    radius_m: float


@dataclass(frozen=True)
class Capsule:
    """Cylinder of `length_m` along local z with hemispherical caps of `radius_m` (total length + 2r)."""

    radius_m: float
    length_m: float


@dataclass(frozen=True)
class Plane:
    normal: Vec3 = (0.0, 0.0, 1.0)
    size_m: tuple[float, float] = (100.0, 100.0)  # SDF's <size> is optional; Gazebo treats the plane as infinite


@dataclass(frozen=True)
class Mesh:
    path: str  # absolute filesystem path, resolved from the uri (model://, file://, relative)
    uri: str  # as written in the SDF
    scale: Vec3 = (1.0, 1.0, 1.0)


Geometry = Box | Cylinder | Sphere | Capsule | Plane | Mesh


@dataclass(frozen=True)
class Surface:
    """Contact friction (SDF <surface><friction><ode> mu/mu2; Gazebo's default is 1.0) and restitution."""

    mu: float = 1.0
    mu2: float = 1.0
    restitution: float = 0.0
    # <ode><fdir1>: the direction `mu` acts along (`mu2` across it), in the link frame at load time (its
    # gz:expressed_in frame resolved; without one, ODE's collision frame); None when not given
    fdir1: Vec3 | None = None


@dataclass(frozen=True)
class Collision:
    name: str
    pose_link: Pose
    geometry: Geometry
    surface: Surface = field(default_factory=Surface)


@dataclass(frozen=True)
class Visual:
    name: str
    pose_link: Pose
    geometry: Geometry
    rgba: tuple[float, float, float, float] | None = None  # <material><diffuse> (or ambient), when given
    laser_retro: float = 0.0  # <laser_retro>: the intensity a lidar ray reports when it hits this visual


@dataclass(frozen=True)
class Inertial:
    mass_kg: float
    pose_link: Pose  # centre of mass and principal-axes orientation, in the link frame
    ixx: float
    ixy: float
    ixz: float
    iyy: float
    iyz: float
    izz: float

    @property
    def diagonal(self) -> Vec3:
        return (self.ixx, self.iyy, self.izz)


# --- sensors -------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Noise:
    """Gaussian noise as SDF writes it; type 'none' means no noise."""

    type: str = "none"
    mean: float = 0.0
    stddev: float = 0.0
    bias_mean: float = 0.0
    bias_stddev: float = 0.0

    @property
    def active(self) -> bool:
        if self.type == "none":
            return False
        return self.stddev > 0 or self.mean != 0 or self.bias_mean != 0 or self.bias_stddev > 0


@dataclass(frozen=True)
class LidarSpec:
    horizontal_samples: int = 640
    horizontal_resolution: float = 1.0
    horizontal_min_angle_rad: float = 0.0
    horizontal_max_angle_rad: float = 0.0
    vertical_samples: int = 1
    vertical_resolution: float = 1.0
    vertical_min_angle_rad: float = 0.0
    vertical_max_angle_rad: float = 0.0
    range_min_m: float = 0.0
    range_max_m: float = 10.0
    range_resolution_m: float = 0.0
    noise: Noise = field(default_factory=Noise)

    @property
    def angle_increment_rad(self) -> float:
        n = self.horizontal_samples
        return (self.horizontal_max_angle_rad - self.horizontal_min_angle_rad) / (n - 1) if n > 1 else 0.0


@dataclass(frozen=True)
class CameraSpec:
    width_px: int = 320
    height_px: int = 240
    horizontal_fov_rad: float = 1.047
    format: str = "R8G8B8"
    clip_near_m: float = 0.1
    clip_far_m: float = 100.0
    noise: Noise = field(default_factory=Noise)
    camera_info_topic: str = ""  # <camera_info_topic>; "" = Gazebo's default beside the image topic
    optical_frame_id: str = ""  # <optical_frame_id>; "" = the sensor's frame id
    lens_intrinsics_px: tuple[float, float, float, float, float] | None = None  # <lens><intrinsics> fx fy cx cy s
    # <lens><projection> p_fx p_fy p_cx p_cy tx ty
    lens_projection_px: tuple[float, float, float, float, float, float] | None = None
    distortion: tuple[float, float, float, float, float] = (0.0, 0.0, 0.0, 0.0, 0.0)  # <distortion> k1 k2 p1 p2 k3
    depth_clip_m: tuple[float | None, float | None] = (None, None)  # <depth_camera><clip> near, far
    triggered: bool = False  # <triggered>: a frame only when a message arrives on the trigger topic
    trigger_topic: str = ""  # <trigger_topic>; "" = Gazebo's default, <image topic>/trigger

    @property
    def vertical_fov_rad(self) -> float:
        return 2.0 * math.atan(math.tan(self.horizontal_fov_rad / 2.0) * self.height_px / self.width_px)


@dataclass(frozen=True)
class ImuSpec:
    angular_velocity_noise: tuple[Noise, Noise, Noise] = (Noise(), Noise(), Noise())
    linear_acceleration_noise: tuple[Noise, Noise, Noise] = (Noise(), Noise(), Noise())


@dataclass(frozen=True)
class AirPressureSpec:
    reference_altitude_m: float = 0.0  # <reference_altitude>: added to the sensor's height in the world
    noise: Noise = field(default_factory=Noise)  # <pressure><noise>, in pascals


@dataclass(frozen=True)
class MagnetometerSpec:
    """<magnetometer><x|y|z><noise>, in tesla."""

    noise: tuple[Noise, Noise, Noise] = (Noise(), Noise(), Noise())


@dataclass(frozen=True)
class NavSatSpec:
    """<navsat> noise: position in degrees (horizontal, on latitude and longitude) and metres (vertical),
    velocity in m/s, as gz-sensors applies them."""

    horizontal_position_noise: Noise = field(default_factory=Noise)
    vertical_position_noise: Noise = field(default_factory=Noise)
    horizontal_velocity_noise: Noise = field(default_factory=Noise)
    vertical_velocity_noise: Noise = field(default_factory=Noise)


SENSOR_TYPES = ("lidar", "imu", "camera", "depth_camera", "rgbd_camera", "air_pressure", "navsat", "magnetometer")


@dataclass(frozen=True)
class Sensor:
    name: str
    type: str  # one of SENSOR_TYPES (gpu_lidar / gpu_ray / ray map to "lidar", depth / rgbd to the cameras)
    sdf_type: str  # as written in the SDF
    link: str  # scoped name of the owning link
    topic: str  # <topic> made absolute; "" when absent (the simulator derives Gazebo's default from the world)
    update_rate_hz: float
    always_on: bool
    visualize: bool
    pose_link: Pose
    pose_world: Pose
    frame_id: str | None = None  # <gz_frame_id> / <frame_id> when given
    lidar: LidarSpec | None = None
    camera: CameraSpec | None = None
    imu: ImuSpec | None = None
    air_pressure: AirPressureSpec | None = None
    navsat: NavSatSpec | None = None
    magnetometer: MagnetometerSpec | None = None


# --- links, joints, frames ------------------------------------------------------------------------------


@dataclass(frozen=True)
class Link:
    name: str  # scoped for links of nested models
    pose_world: Pose
    pose_model: Pose
    inertial: Inertial | None
    collisions: tuple[Collision, ...] = ()
    visuals: tuple[Visual, ...] = ()
    sensors: tuple[Sensor, ...] = ()
    gravity: bool = True
    kinematic: bool = False
    self_collide: bool = False


JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "ball")


@dataclass(frozen=True)
class JointLimits:
    """SDF <axis><limit>; SDF's defaults mean 'unlimited' (±1e16 position, -1 effort/velocity = no limit)."""

    lower: float = -1e16
    upper: float = 1e16
    effort: float = math.inf
    velocity: float = math.inf

    @property
    def bounded(self) -> bool:
        return self.lower > -1e15 and self.upper < 1e15 and self.lower <= self.upper


@dataclass(frozen=True)
class JointDynamics:
    damping: float = 0.0
    friction: float = 0.0
    spring_reference: float = 0.0
    spring_stiffness: float = 0.0


@dataclass(frozen=True)
class Joint:
    name: str
    type: str  # one of JOINT_TYPES
    parent: str  # scoped link name, or "world"
    child: str  # scoped link name
    pose_world: Pose  # the joint frame (SDF: given in the child frame by default), resolved
    pose_child: Pose  # the joint frame in the child link's frame
    axis_world: Vec3 | None  # unit axis in world frame (None for fixed and ball)
    axis_child: Vec3 | None  # the same axis in the child link's frame
    limits: JointLimits = field(default_factory=JointLimits)
    dynamics: JointDynamics = field(default_factory=JointDynamics)
    # <axis><mimic> (SDF 1.11; URDF's <mimic>): (leader joint, multiplier, offset), this joint's position being
    # multiplier · leader + offset. SDF's <reference> r is folded into the offset (offset − multiplier · r).
    mimic: tuple[str, float, float] | None = None

    @property
    def moves(self) -> bool:
        return self.type != "fixed"


@dataclass(frozen=True)
class Frame:
    name: str  # scoped
    attached_to: str  # the link (scoped) this frame is rigidly attached to, after following frame chains
    pose_world: Pose
    pose_model: Pose


_SYSTEM_FILENAME = re.compile(r"^(?:gz-sim|ignition-gazebo)\d*-(.+)-system$")

# --- plugins and ros2_control -----------------------------------------------------------------------------


@dataclass(frozen=True)
class Plugin:
    """A <plugin>: `params` holds first-level child elements' text; `xml` the whole element for anything deeper."""

    name: str
    filename: str
    params: tuple[tuple[str, str], ...] = ()
    xml: str = ""

    @property
    def system(self) -> str:
        """The Gazebo system this plugin loads, however its filename is spelled.

        'gz-sim-diff-drive-system', 'libgz-sim8-diff-drive-system.so' and 'ignition-gazebo-diff-drive-system'
        all give 'diff-drive'; gz_ros2_control gives 'gz_ros2_control'; anything else its bare filename.
        """
        base = self.filename.rsplit("/", 1)[-1].removesuffix(".so").removeprefix("lib")
        if "gz_ros2_control" in base or "ign_ros2_control" in base:
            return "gz_ros2_control"
        match = _SYSTEM_FILENAME.match(base)
        return match.group(1) if match else base

    def get(self, tag: str, default: str | None = None) -> str | None:
        for k, v in self.params:
            if k == tag:
                return v
        return default

    def get_all(self, tag: str) -> list[str]:
        return [v for k, v in self.params if k == tag]

    def as_dict(self) -> dict[str, str]:
        """First-level children as a dict (first occurrence wins for repeated tags)."""
        out: dict[str, str] = {}
        for k, v in self.params:
            out.setdefault(k, v)
        return out


@dataclass(frozen=True)
class Ros2ControlInterface:
    name: str  # position, velocity, effort, …
    initial_value: float | None = None
    params: tuple[tuple[str, str], ...] = ()  # <param name="min">-1</param>, … (min/max/initial_value excluded)
    min: float | None = None
    max: float | None = None
    data_type: str = "double"  # the element's data_type attribute, as ros2_control's component parser reads it
    enable_limits: bool = True  # <limits enable="false"/>: min/max are no joint limits for the resource manager


@dataclass(frozen=True)
class Ros2ControlJoint:
    name: str
    command_interfaces: tuple[Ros2ControlInterface, ...] = ()
    state_interfaces: tuple[Ros2ControlInterface, ...] = ()
    params: tuple[tuple[str, str], ...] = ()
    enable_limits: bool = True  # <limits enable="false"/> directly in the <joint>: none of its limits apply


@dataclass(frozen=True)
class Ros2Control:
    """A <ros2_control> block (system, actuator or sensor hardware)."""

    name: str
    type: str  # system | actuator | sensor
    hardware_plugin: str  # e.g. gz_ros2_control/GazeboSimSystem, mock_components/GenericSystem
    hardware_params: tuple[tuple[str, str], ...] = ()
    joints: tuple[Ros2ControlJoint, ...] = ()
    sensors: tuple[Ros2ControlJoint, ...] = ()  # same shape: name + state interfaces + params
    gpios: tuple[Ros2ControlJoint, ...] = ()

    def hardware_param(self, name: str, default: str | None = None) -> str | None:
        return dict(self.hardware_params).get(name, default)


# --- lights, physics, models, world ----------------------------------------------------------------------


@dataclass(frozen=True)
class Light:
    name: str
    type: str  # directional | point | spot
    pose_world: Pose
    direction: Vec3 = (0.0, 0.0, -1.0)
    diffuse: tuple[float, float, float, float] = (1.0, 1.0, 1.0, 1.0)
    specular: tuple[float, float, float, float] = (0.1, 0.1, 0.1, 1.0)
    cast_shadows: bool = False


@dataclass(frozen=True)
class Physics:
    max_step_size_s: float = 0.001
    real_time_factor: float = 1.0
    gravity: Vec3 = (0.0, 0.0, -9.8)
    real_time_update_rate_hz: float = 1000.0
    # the world's <magnetic_field>, tesla, in the world frame (sdformat's default)
    magnetic_field_t: Vec3 = (5.5645e-6, 22.8758e-6, -42.3884e-6)


@dataclass(frozen=True)
class Model:
    name: str
    static: bool
    pose_world: Pose  # the model frame
    links: tuple[Link, ...]
    joints: tuple[Joint, ...] = ()
    frames: tuple[Frame, ...] = ()
    plugins: tuple[Plugin, ...] = ()
    ros2_control: tuple[Ros2Control, ...] = ()
    canonical_link: str = ""
    self_collide: bool = False
    source: str = ""  # file the model came from ("<string>" when parsed from text)
    ignored: tuple[str, ...] = ()  # elements read but not simulated (e.g. a magnetometer sensor), one line each

    def link(self, name: str) -> Link:
        for link in self.links:
            if link.name == name:
                return link
        raise KeyError(name)

    def joint(self, name: str) -> Joint:
        for joint in self.joints:
            if joint.name == name:
                return joint
        raise KeyError(name)

    def frame(self, name: str) -> Frame:
        for fr in self.frames:
            if fr.name == name:
                return fr
        raise KeyError(name)

    def sensors(self) -> Iterator[Sensor]:
        for link in self.links:
            yield from link.sensors

    def plugin(self, filename_or_name: str) -> Plugin | None:
        """The first plugin whose filename or name contains the given text (e.g. 'diff-drive')."""
        for p in self.plugins:
            if filename_or_name in p.filename or filename_or_name in p.name:
                return p
        return None

    def root_link(self) -> str:
        """The link no joint has as child (the canonical link when several qualify)."""
        children = {j.child for j in self.joints}
        roots = [link.name for link in self.links if link.name not in children]
        if self.canonical_link in roots:
            return self.canonical_link
        return roots[0] if roots else self.canonical_link

    def __rich__(self) -> object:
        from diffctl.console import table

        rows = []
        for link in self.links:
            x, y, z = link.pose_model.xyz
            mass = f"{link.inertial.mass_kg:g}" if link.inertial else "-"
            rows.append(("link", link.name, f"{x:.3f} {y:.3f} {z:.3f}", mass, ", ".join(s.name for s in link.sensors)))
        for j in self.joints:
            rows.append((f"joint ({j.type})", j.name, f"{j.parent} → {j.child}", "", ""))
        columns = ["kind", "name", "pose (model) / parent → child", "mass kg", "sensors"]
        return table(f"model {self.name}", columns, rows)


@dataclass(frozen=True)
class SphericalCoordinates:
    """<spherical_coordinates>: the geodetic position of the world's origin, and the heading of its x axis."""

    latitude_deg: float = 0.0
    longitude_deg: float = 0.0
    elevation_m: float = 0.0
    heading_deg: float = 0.0
    surface_model: str = "EARTH_WGS84"
    world_frame_orientation: str = "ENU"


@dataclass(frozen=True)
class World:
    name: str
    physics: Physics
    models: tuple[Model, ...] = ()
    lights: tuple[Light, ...] = ()
    plugins: tuple[Plugin, ...] = ()
    source: str = ""
    spherical_coordinates: SphericalCoordinates | None = None  # where the world's origin is on the planet

    def model(self, name: str) -> Model:
        for m in self.models:
            if m.name == name:
                return m
        raise KeyError(name)

    def all_plugins(self) -> Iterator[tuple[str | None, Plugin]]:
        """(model name or None for world plugins, plugin) for every plugin, for 'ignored plugin' reports."""
        for p in self.plugins:
            yield None, p
        for m in self.models:
            for p in m.plugins:
                yield m.name, p
