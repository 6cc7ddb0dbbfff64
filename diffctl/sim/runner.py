"""A running simulation: the physics world, its models with their sensors and systems, sim-side topics.

`Simulation` wires the parts together; the loop itself is `stepper.Stepper`, the world services are in
`services.py`. Sim-side gz topics: `/clock` (gz.msgs.Clock every 10 ms of sim time), `/model/<m>/pose`
(gz.msgs.Pose_V ground truth, 50 Hz), sensors on their SDF topics, and what the systems publish. Nothing is
encoded for a topic nobody subscribes to, and cameras render only while someone does.
"""

from __future__ import annotations

import importlib
import re
import threading
import time
import zlib
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
import pybullet as pb

from diffctl.bus import gz
from diffctl.description.model import Model, World
from diffctl.errors import DescriptionError, RuntimeFailure
from diffctl.sim.entity import Entity
from diffctl.sim.log import Logger
from diffctl.sim.plugins.base import PluginContext, SystemPlugin, bool_param, rate_period_ns
from diffctl.sim.plugins.gz_ros2_control import GzRos2Control, PreparedManager
from diffctl.sim.plugins.system_names import system_kind
from diffctl.sim.sensors import Camera, CameraSensor, CameraTask, Imu, Lidar, RenderRate
from diffctl.sim.sensors import topics as sensor_topics
from diffctl.sim.stepper import Stepper, Task
from diffctl.sim.transport import GzPublisher, SimTransport
from diffctl.sim.world import PhysicsWorld

if TYPE_CHECKING:
    from diffctl.sim.sensors import AirPressure, Magnetometer, NavSat
    from diffctl.sim.sensors.magnetometer import EarthFieldParams

CLOCK_PERIOD_NS = 10_000_000
# /clock ticks every 10 ms of sim time, but faster than real time no more often than every 4 ms of wall time
# (≤ 250 Hz): every sim-time node receives each tick, and Zenoh's transport costs each receiver tens of µs
# per sample whatever it does with it, so at 20× real time 2 kHz of ticks would cost every such node a good
# part of a core. (Gazebo classic's /clock was throttled by wall time too.) A paused world or a reset
# publishes its time at once.
CLOCK_MIN_WALL_NS = 4_000_000
POSE_RATE_HZ = 50.0
DEFAULT_LIGHT_DIRECTION = (-0.5, 0.1, -0.9)
# Model names become Zenoh key chunks.
_NAME_RE = re.compile(r"^[A-Za-z0-9_.\-]+$")

# Gazebo systems whose job the simulator does natively: accepted without a word.
NATIVE_SYSTEMS = {
    "physics",
    "user-commands",
    "scene-broadcaster",
    "sensors",
    "imu",
    "air-pressure",
    "navsat",
    "contact",
    "magnetometer",  # its Earth field options are read by _earth_field
}
CONTROL_SYSTEMS = ("gz_ros2_control", "ign_ros2_control")
# Systems built from the plugin element alone.
JOINT_SYSTEMS: dict[str, tuple[str, str]] = {
    "joint-position-controller": ("joint_position_controller", "JointPositionController"),
    "joint-controller": ("joint_controller", "JointController"),
    "velocity-control": ("velocity_control", "VelocityControl"),
    "joint-trajectory-controller": ("joint_trajectory_controller", "JointTrajectoryController"),
    "apply-joint-force": ("apply_joint_force", "ApplyJointForce"),
}
MODEL_SYSTEMS = {
    "diff-drive",
    "mecanum-drive",
    "ackermann-steering",
    "joint-position-controller",
    "joint-controller",
    "velocity-control",
    "joint-trajectory-controller",
    "apply-joint-force",
    "tracked-vehicle",
    "track-controller",
    "joint-state-publisher",
    "odometry-publisher",
    "linearbatteryplugin",
    "pose-publisher",
    *CONTROL_SYSTEMS,
}


def _plugin(module: str, name: str) -> Any:
    """A system plugin's class, imported when a model first uses it: a world uses one or two of the fifteen, and
    importing them all was ~35 ms of every simulator's start (and of the fork server's)."""
    return getattr(importlib.import_module(f"diffctl.sim.plugins.{module}"), name)


def system_name(filename: str, name: str = "") -> str:
    """`libgz-sim-diff-drive-system.so` → `diff-drive`; `gz_ros2_control-system` → `gz_ros2_control` (see
    plugins/system_names.py for the spellings)."""
    return system_kind(filename, name)


@dataclass
class ModelRuntime:
    entity: Entity
    plugins: list[SystemPlugin] = field(default_factory=list)
    tasks: list[Task] = field(default_factory=list)
    publishers: list[GzPublisher] = field(default_factory=list)
    imus: list[Imu] = field(default_factory=list)
    sensors: list[Lidar | Imu | CameraSensor | AirPressure | NavSat | Magnetometer] = field(default_factory=list)
    control: GzRos2Control | None = None  # the model's controller manager (gz_ros2_control)


class Simulation:
    def __init__(
        self,
        world: World,
        *,
        gui: bool = False,
        rtf: float | None = None,
        paused: bool = True,
        seed: int = 0,
        log: Logger | None = None,
        session: Any = None,
    ) -> None:
        self.world_model = world
        self.name = world.name
        self.log = log or Logger("sim", "WARN")
        self.physics = PhysicsWorld(world.physics, gui=gui)
        target_rtf = world.physics.real_time_factor if rtf is None else rtf
        self.stepper = Stepper(self.physics.step, self.physics.step_ns, rtf=target_rtf, paused=paused)
        self.transport = SimTransport(session, self.stepper.call_soon, self.log) if session is not None else None
        if self.transport is not None:
            self.stepper.batch_hooks.append((self.transport.outbox.hold, self.transport.outbox.release))
        # The hosted controller managers' samples wait for the end of the batch as well: one wake of their
        # publishing thread per batch, not one per manager (a fleet's managers all cycle on the same step).
        self.stepper.batch_hooks.append(_publishing_held_per_batch())
        self.ctx = PluginContext(self.stepper, self.transport, self.log, world.name)
        self.seed = seed
        self.models: dict[str, ModelRuntime] = {}
        self._retro: dict[tuple[int, int], float] | None = None  # laser_retro by PyBullet link, built on demand
        lights = [lt for lt in world.lights if lt.type == "directional"]
        self.light_direction = lights[0].direction if lights else DEFAULT_LIGHT_DIRECTION
        self.wall_start_s = time.time()
        self._clock_pub = self.transport.publisher("/clock", "gz.msgs.Clock") if self.transport else None
        self._clock_sent = (-1, 0)  # (sim ns, monotonic wall ns) of the last /clock sample
        self.stepper.add_task("clock", CLOCK_PERIOD_NS, self._publish_clock)
        self.stepper.idle_hooks.append(self._flush_clock)
        try:
            for m in world.models:
                self.spawn(m)
        except Exception:
            self.close()
            raise
        self._report_ignored(world)

    # --- models ----------------------------------------------------------------------------------------

    def spawn(self, model: Model, description: str = "", prepared: PreparedManager | None = None) -> Entity:
        """Add `model` (already at its spawn pose) with its sensors and systems; sim thread only.
        `description` is the text it came from (the robot_description its controller manager gets);
        `prepared`, its controller manager built off the sim thread (`prepare_manager`), adopted here. The
        caller closes a prepared manager this raised before adopting."""
        if not _NAME_RE.match(model.name):
            raise DescriptionError(
                f"model name {model.name!r} may hold only letters, digits, '_', '-' and '.'", field="name"
            )
        if model.name in self.models:
            raise RuntimeFailure(f"an entity named {model.name!r} already exists", hint="choose another name")
        entity = self.physics.add_model(model)
        if entity.plan.notes:
            self.log.warn(f"model {model.name!r}: " + "; ".join(entity.plan.notes))
        rt = ModelRuntime(entity)
        self.models[model.name] = rt
        self._retro = None
        try:
            self._add_systems(rt, description, prepared)
            self._add_sensors(rt)
            owned = {t for p in rt.plugins for t in getattr(p, "topics", ())}
            if not model.static and self.transport is not None and f"/model/{model.name}/pose" not in owned:
                pub = self.transport.publisher(f"/model/{model.name}/pose", "gz.msgs.Pose_V")
                rt.publishers.append(pub)
                period = rate_period_ns(POSE_RATE_HZ, self.stepper.step_ns)
                rt.tasks.append(self.stepper.add_task(f"pose:{model.name}", period, self._pose_task(entity, pub)))
        except Exception:
            self.remove(model.name)
            raise
        if self.physics.gui and not model.static:
            self._look_at(entity)
        return entity

    def _earth_field(self) -> EarthFieldParams | None:
        """The Earth's field for magnetometers when the world is placed on it (gz-sim's Magnetometer system)."""
        from diffctl.sim.sensors.magnetometer import EarthFieldParams

        origin = self.world_model.spherical_coordinates
        if origin is None:
            return None
        system = next(
            (p for p in self.world_model.plugins if system_kind(p.filename, p.name) == "magnetometer"), None
        )
        source = self.world_model.source
        if system is None:
            return EarthFieldParams(origin)
        return EarthFieldParams(
            origin,
            units_gauss=bool_param(system, "use_units_gauss", True, source=source),
            ned=bool_param(system, "use_earth_frame_ned", True, source=source),
        )

    def laser_retro(self) -> dict[tuple[int, int], float]:
        """(PyBullet body, link index) → the `<laser_retro>` of the visuals there, for every model that sets
        one (the largest where one PyBullet link carries several); rebuilt after a spawn or a removal."""
        if self._retro is None:
            retro: dict[tuple[int, int], float] = {}
            for rt in self.models.values():
                for link in rt.entity.model.links:
                    value = max((v.laser_retro for v in link.visuals), default=0.0)
                    if value:
                        body, index, _ = rt.entity.link_frame(link.name)
                        retro[(body, index)] = max(value, retro.get((body, index), value))
            self._retro = retro
        return self._retro

    def remove(self, name: str) -> None:
        rt = self.models.pop(name, None)
        if rt is None:
            raise RuntimeFailure(f"no entity named {name!r}", hint=f"entities: {', '.join(self.models) or 'none'}")
        self._retro = None
        for p in rt.plugins:
            p.close()
        for t in rt.tasks:
            self.stepper.remove_task(t)
        if self.transport is not None:
            for pub in rt.publishers:
                self.transport.release(pub)
        self.physics.remove(name)
        self.stepper.reschedule()

    def prepare_manager(self, model: Model, description: str = "") -> PreparedManager | None:
        """The controller manager of `model` (one gz_ros2_control plugin), built from any thread: its node,
        parameters and manager take tens of milliseconds that need not stop the simulation loop. None when the
        model has no such plugin, or more than one (the spawn reports that)."""
        plugins = [p for p in model.plugins if system_name(p.filename, p.name) in CONTROL_SYSTEMS]
        if len(plugins) != 1 or self.transport is None:
            return None
        return PreparedManager(self.ctx, model, plugins[0], description)

    def _add_systems(self, rt: ModelRuntime, description: str = "", prepared: PreparedManager | None = None) -> None:
        model = rt.entity.model
        # A TrackedVehicle commands the tracks of its model: those are made first, whatever the plugin order.
        tracks = [
            _plugin("track_controller", "TrackController")(self.ctx, rt.entity, p)
            for p in model.plugins
            if system_name(p.filename, p.name) == "track-controller"
        ]
        rt.plugins.extend(tracks)
        if tracks:
            rt.plugins.append(_plugin("track_belts", "TrackBelts")(self.ctx, rt.entity, tracks))
        for plugin in model.plugins:
            kind = system_name(plugin.filename, plugin.name)
            if kind == "tracked-vehicle":
                rt.plugins.append(_plugin("tracked_vehicle", "TrackedVehicle")(self.ctx, rt.entity, plugin, tracks))
            elif kind == "diff-drive":
                canonical = model.canonical_link or model.root_link()
                params = _plugin("diff_drive", "DiffDriveParams").from_plugin(
                    plugin, model.name, canonical, model.source)
                rt.plugins.append(_plugin("diff_drive", "DiffDrive")(self.ctx, rt.entity, params))
            elif kind == "mecanum-drive":
                canonical = model.canonical_link or model.root_link()
                mecanum = _plugin("mecanum_drive", "MecanumDriveParams").from_plugin(
                    plugin, model.name, canonical, model.source)
                rt.plugins.append(_plugin("mecanum_drive", "MecanumDrive")(self.ctx, rt.entity, mecanum))
            elif kind == "ackermann-steering":
                canonical = model.canonical_link or model.root_link()
                ackermann = _plugin("ackermann_steering", "AckermannSteeringParams").from_plugin(
                    plugin, model.name, canonical, model.source)
                rt.plugins.append(_plugin("ackermann_steering", "AckermannSteering")(self.ctx, rt.entity, ackermann))
            elif kind in JOINT_SYSTEMS:
                rt.plugins.append(_plugin(*JOINT_SYSTEMS[kind])(self.ctx, rt.entity, plugin))
            elif kind == "joint-state-publisher":
                rt.plugins.append(_plugin("joint_state_publisher", "JointStatePublisher")(self.ctx, rt.entity, plugin))
            elif kind == "pose-publisher":
                rt.plugins.append(_plugin("pose_publisher", "PosePublisher")(self.ctx, rt.entity, plugin))
            elif kind == "linearbatteryplugin":
                rt.plugins.append(_plugin("linear_battery", "LinearBatteryPlugin")(self.ctx, rt.entity, plugin))
            elif kind == "odometry-publisher":
                rng = self.sensor_rng(model.name, f"odometry_publisher:{plugin.name}")
                rt.plugins.append(_plugin("odometry_publisher", "OdometryPublisher")(self.ctx, rt.entity, plugin, rng))
            elif kind in CONTROL_SYSTEMS:
                if rt.control is not None:
                    raise DescriptionError(
                        f"model {model.name!r} has the gz_ros2_control plugin twice",
                        source=model.source or None,
                        field=f"plugin {plugin.filename}",
                    )
                rt.control = GzRos2Control(self.ctx, rt.entity, plugin, description, prepared)
                rt.plugins.append(rt.control)

    def _add_sensors(self, rt: ModelRuntime) -> None:
        entity = rt.entity
        step_ns = self.stepper.step_ns
        for s in entity.model.sensors():
            # update_rate 0 means "every step" in Gazebo.
            period = rate_period_ns(s.update_rate_hz, step_ns) if s.update_rate_hz > 0 else step_ns
            rng = self.sensor_rng(entity.name, s.name)
            sensor: Lidar | Imu | CameraSensor | AirPressure | NavSat | Magnetometer
            if s.type == "lidar":
                sensor = Lidar(entity, s, rng, self.laser_retro)
            elif s.type == "air_pressure":
                from diffctl.sim.sensors.air_pressure import AirPressure

                sensor = AirPressure(entity, s, rng)
            elif s.type == "magnetometer":
                from diffctl.sim.sensors.magnetometer import Magnetometer

                sensor = Magnetometer(entity, s, self.physics.physics.magnetic_field_t, rng, self._earth_field())
            elif s.type == "navsat":
                from diffctl.sim.sensors.navsat import NavSat, origin_problem

                origin = self.world_model.spherical_coordinates
                problem = origin_problem(origin)
                if problem is not None or origin is None:
                    self.log.warn(f"navsat {entity.name}::{s.link}::{s.name}: {problem}")
                    continue
                sensor = NavSat(entity, s, rng, origin)
            elif s.type == "imu":
                sensor = Imu(entity, s, self.physics.physics.gravity, rng)
                rt.imus.append(sensor)
            else:
                sensor = CameraSensor(Camera(entity, s, rng, self.light_direction, self.physics.all_flat_planes))
                for note in sensor.notes:
                    self.log.warn(f"{s.type} {sensor.name}: {note}")
            rt.sensors.append(sensor)
            if self.transport is None:
                continue
            base = sensor_topics.base_topic(s, self.name, entity.name)
            pubs = {o.name: self.transport.publisher(o.topic, o.gz_type) for o in sensor_topics.outputs(s, base)}
            rt.publishers.extend(pubs.values())
            name = f"{s.type}:{entity.name}:{s.name}"
            if isinstance(sensor, CameraSensor):
                job = CameraTask(sensor, pubs, RenderRate(period, step_ns), lambda: self.stepper.rtf, self.log.warn)
                if s.type == "camera" and s.camera is not None and s.camera.triggered:
                    job.triggered = True
                    topic = s.camera.trigger_topic or base.rstrip("/") + "/trigger"
                    rt.publishers.append(  # released with the model
                        self.transport.subscribe(topic, "gz.msgs.Boolean", lambda _m, job=job: job.trigger())
                    )
                job.task = self.stepper.add_task(name, period, job)
                rt.tasks.append(job.task)
                continue
            if isinstance(sensor, Lidar):
                rt.tasks.append(self.stepper.add_task(name, period, self._outputs_task(sensor, pubs)))
                continue
            (pub,) = pubs.values()
            if isinstance(sensor, Imu) and period > step_ns:
                # Acceleration is the velocity difference over the last step: remember it one step earlier.
                first = self.stepper.sim_time_ns + period - step_ns
                pre = self._imu_pre(sensor, pub)
                rt.tasks.append(self.stepper.add_task(name + ":pre", period, pre, first_ns=first))
            rt.tasks.append(self.stepper.add_task(name, period, self._sensor_task(sensor, pub)))

    def sensor_rng(self, model: str, sensor: str) -> np.random.Generator:
        """Each sensor's own noise stream from the seed and its name: which sensors are read (they sample only
        while subscribed) never changes another's noise."""
        return np.random.default_rng([self.seed, zlib.crc32(f"{model}::{sensor}".encode())])

    @staticmethod
    def _sensor_task(sensor: Any, pub: GzPublisher) -> Any:
        def task(sim_time_ns: int) -> None:
            if pub.matched:
                pub.publish(sensor.sample(sim_time_ns))

        return task

    @staticmethod
    def _outputs_task(sensor: Lidar, pubs: dict[str, GzPublisher]) -> Any:
        """One sample feeds every subscribed output (a lidar's scan and points)."""

        def task(sim_time_ns: int) -> None:
            wanted = {name for name, pub in pubs.items() if pub.matched}
            for name, msg in sensor.messages(sim_time_ns, wanted).items():
                pubs[name].publish(msg)

        return task

    @staticmethod
    def _imu_pre(imu: Imu, pub: GzPublisher) -> Any:
        def task(sim_time_ns: int) -> None:
            if pub.matched:
                imu.remember(sim_time_ns)

        return task

    def _pose_task(self, entity: Entity, pub: GzPublisher) -> Any:
        def task(sim_time_ns: int) -> None:
            if not pub.matched:
                return
            p = entity.pose()
            pub.publish(
                {
                    "header": gz.header(sim_time_ns),
                    "pose": [
                        {
                            "name": entity.name,
                            "header": gz.header(sim_time_ns, "world", entity.name),
                            "position": {"x": p.xyz[0], "y": p.xyz[1], "z": p.xyz[2]},
                            "orientation": {"x": p.quat[0], "y": p.quat[1], "z": p.quat[2], "w": p.quat[3]},
                        }
                    ],
                }
            )

        return task

    def _look_at(self, entity: Entity) -> None:
        p = entity.pose().xyz
        pb.resetDebugVisualizerCamera(0.7, 50.0, -30.0, p, physicsClientId=self.physics.client)

    # --- world ---------------------------------------------------------------------------------------

    def reset(self) -> None:
        """Gazebo's world reset: sim time 0, every model back at its spawn pose, systems reset."""
        self.stepper.reset_time()
        self.physics.reset()
        for rt in self.models.values():
            for p in rt.plugins:
                p.reset()
            for imu in rt.imus:
                imu.reset()
        self.stepper.run_due()

    def _publish_clock(self, sim_time_ns: int) -> None:
        pub = self._clock_pub
        if pub is None or not pub.matched:
            return
        mono_ns = time.monotonic_ns()
        last_sim_ns, last_mono_ns = self._clock_sent
        if last_sim_ns <= sim_time_ns and mono_ns - last_mono_ns < CLOCK_MIN_WALL_NS:
            return
        self._clock_sent = (sim_time_ns, mono_ns)
        wall_ns = time.time_ns()
        real_ns = max(0, wall_ns - int(self.wall_start_s * 1e9))
        pub.put_raw(gz.clock(sim_time_ns, real_ns, wall_ns))

    def _flush_clock(self) -> None:
        """While paused: the time a throttled tick left unsent goes out now."""
        now = self.stepper.sim_time_ns
        if self._clock_sent[0] != now:
            self._clock_sent = (now - 1, 0)
            self._publish_clock(now)

    def _report_ignored(self, world: World) -> None:
        lines = []
        for model_name, plugin in world.all_plugins():
            kind = system_name(plugin.filename, plugin.name)
            if (model_name is None and kind not in NATIVE_SYSTEMS) or (
                model_name is not None and kind not in MODEL_SYSTEMS | NATIVE_SYSTEMS
            ):
                where = f"model {model_name!r}" if model_name else f"world {world.name!r}"
                lines.append(f"plugin {plugin.filename} ({plugin.name}) on {where}")
        for m in world.models:
            lines.extend(f"model {m.name!r}: {text}" for text in m.ignored)
        if lines:
            self.log.warn("ignored (not simulated): " + "; ".join(lines))

    def model_ignored(self, model: Model) -> list[str]:
        out = [
            f"plugin {p.filename} ({p.name})"
            for p in model.plugins
            if system_name(p.filename, p.name) not in MODEL_SYSTEMS | NATIVE_SYSTEMS
        ]
        return out + list(model.ignored)

    def run(self, stop: threading.Event) -> None:
        self.stepper.run(stop)

    def close(self) -> None:
        for name in list(self.models):
            try:
                self.remove(name)
            except Exception:
                pass
        if self.transport is not None:
            self.transport.close()
        self.physics.close()


def _publishing_held_per_batch() -> tuple[Callable[[], None], Callable[[], None]]:
    """(begin, end) of a batch of tasks: realtime_publisher's hold and release on the sim thread, so a manager's
    own hold inside its cycle finds it held and leaves the wake-up to the batch's end."""
    from diffctl.control import realtime_publisher

    held: list[Any] = [None]

    def begin() -> None:
        held[0] = realtime_publisher.hold()

    def end() -> None:
        t, held[0] = held[0], None
        realtime_publisher.release(t)

    return begin, end

