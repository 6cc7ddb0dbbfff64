"""Gazebo's PosePublisher system (`gz-sim-pose-publisher-system`): poses of a model's entities, each relative to
its parent, on `/model/<model>/pose` (and `/model/<model>/pose_static` with `<static_publisher>`).

Parameters as gz-sim reads them: `<publish_link_pose>` (true), `<publish_visual_pose>`,
`<publish_collision_pose>`, `<publish_sensor_pose>`, `<publish_nested_model_pose>` (false),
`<publish_model_pose>` (defaults to publish_nested_model_pose), `<use_pose_vector_msg>` (false: one gz.msgs.Pose
per entity; true: one gz.msgs.Pose_V), `<update_frequency>` (Hz; -1, the default, every step),
`<static_publisher>` (false) and `<static_update_frequency>` (defaults to update_frequency). Each pose's
header has `frame_id` = its parent's scoped name (the model's parent is the world) and `child_frame_id` = its
own (`robot::base_link::imu`). With `<static_publisher>`, links moved by a non-fixed joint (except the
canonical link) go on `pose`, everything else on `pose_static`. Nested models are not modelled here: their
links are published relative to the top model.
"""

from __future__ import annotations

from dataclasses import dataclass

from diffctl.bus import gz
from diffctl.description.model import Plugin
from diffctl.description.pose import Pose
from diffctl.sim.entity import Entity
from diffctl.sim.plugins.base import PluginContext, SystemPlugin, bool_param, float_param, rate_period_ns


@dataclass(frozen=True)
class PosePublisherParams:
    link: bool
    visual: bool
    collision: bool
    sensor: bool
    nested_model: bool
    model: bool
    pose_vector: bool
    rate_hz: float  # <= 0: every step
    static_publisher: bool
    static_rate_hz: float

    @staticmethod
    def from_plugin(plugin: Plugin, source: str = "") -> PosePublisherParams:
        def flag(tag: str, default: bool) -> bool:
            return bool_param(plugin, tag, default, source=source)

        nested = flag("publish_nested_model_pose", False)
        rate = float_param(plugin, "update_frequency", -1.0, source=source)
        rate = -1.0 if rate is None else rate
        static_rate = float_param(plugin, "static_update_frequency", rate, source=source)
        return PosePublisherParams(
            link=flag("publish_link_pose", True),
            visual=flag("publish_visual_pose", False),
            collision=flag("publish_collision_pose", False),
            sensor=flag("publish_sensor_pose", False),
            nested_model=nested,
            model=flag("publish_model_pose", nested),
            pose_vector=flag("use_pose_vector_msg", False),
            rate_hz=rate,
            static_publisher=flag("static_publisher", False),
            static_rate_hz=rate if static_rate is None else static_rate,
        )


@dataclass(frozen=True)
class _Item:
    frame_id: str
    child_frame_id: str
    link: str | None  # a link whose pose in the model is read live; None: a fixed pose
    fixed: Pose | None  # the pose relative to the parent when it never changes (visuals, collisions, sensors)
    is_model: bool = False


class PosePublisher(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, plugin: Plugin) -> None:
        self.ctx, self.entity = ctx, entity
        self.p = PosePublisherParams.from_plugin(plugin, entity.model.source)
        m = entity.model
        self.topic = f"/model/{m.name}/pose"
        self.static_topic = self.topic + "_static"
        self.topics = (self.topic, self.static_topic) if self.p.static_publisher else (self.topic,)
        items: list[_Item] = []
        if self.p.model:
            items.append(_Item(ctx.world_name, m.name, None, None, is_model=True))
        for link in m.links:
            link_frame = f"{m.name}::{link.name}"
            if self.p.link:
                items.append(_Item(m.name, link_frame, link.name, None))
            if self.p.visual:
                items.extend(_Item(link_frame, f"{link_frame}::{v.name}", None, v.pose_link) for v in link.visuals)
            if self.p.collision:
                items.extend(_Item(link_frame, f"{link_frame}::{c.name}", None, c.pose_link) for c in link.collisions)
            if self.p.sensor:
                items.extend(_Item(link_frame, f"{link_frame}::{s.name}", None, s.pose_link) for s in link.sensors)
        canonical = m.canonical_link or m.root_link()
        moving = {n for j in m.joints if j.type != "fixed" for n in (j.parent, j.child)} - {canonical, "world"}
        if self.p.static_publisher:
            self.dynamic = [it for it in items if it.link in moving]
            self.static = [it for it in items if it.link not in moving]
        else:
            self.dynamic, self.static = items, []
        msg_type = "gz.msgs.Pose_V" if self.p.pose_vector else "gz.msgs.Pose"
        t = ctx.transport
        self._pub = t.publisher(self.topic, msg_type) if t else None
        self._static_pub = t.publisher(self.static_topic, msg_type) if t and self.p.static_publisher else None
        step_ns = ctx.stepper.step_ns
        self._tasks = [
            ctx.stepper.add_task(
                f"pose_publisher:{m.name}", self._period(self.p.rate_hz, step_ns), self._publisher(False)
            )
        ]
        if self.p.static_publisher:
            period = self._period(self.p.static_rate_hz, step_ns)
            self._tasks.append(ctx.stepper.add_task(f"pose_publisher_static:{m.name}", period, self._publisher(True)))
        self.last: dict[bool, list[dict]] = {False: [], True: []}

    @staticmethod
    def _period(rate_hz: float, step_ns: int) -> int:
        return rate_period_ns(rate_hz, step_ns) if rate_hz > 0 else step_ns

    def poses(self, sim_time_ns: int, static: bool) -> list[dict]:
        """The gz.msgs.Pose messages of the static or the dynamic group at `sim_time_ns`."""
        model_pose = self.entity.pose()
        inv = model_pose.inverse()
        out = []
        for it in self.static if static else self.dynamic:
            if it.is_model:
                pose = model_pose
            elif it.link is not None:
                pose = inv.compose(self.entity.link_pose(it.link))
            else:
                assert it.fixed is not None
                pose = it.fixed
            x, y, z = pose.xyz
            qx, qy, qz, qw = pose.quat
            out.append(
                {
                    "name": it.child_frame_id,
                    "header": gz.header(sim_time_ns, it.frame_id, it.child_frame_id),
                    "position": {"x": x, "y": y, "z": z},
                    "orientation": {"x": qx, "y": qy, "z": qz, "w": qw},
                }
            )
        return out

    def _publisher(self, static: bool):
        def task(sim_time_ns: int) -> None:
            pub = self._static_pub if static else self._pub
            if pub is None or not pub.matched or not (self.static if static else self.dynamic):
                return
            poses = self.poses(sim_time_ns, static)
            self.last[static] = poses
            if self.p.pose_vector:
                pub.publish({"header": gz.header(sim_time_ns), "pose": poses})
            else:
                for pose in poses:
                    pub.publish(pose)

        return task

    def close(self) -> None:
        for task in self._tasks:
            self.ctx.stepper.remove_task(task)
        t = self.ctx.transport
        if t is not None:
            for pub in (self._pub, self._static_pub):
                if pub is not None:
                    t.release(pub)
