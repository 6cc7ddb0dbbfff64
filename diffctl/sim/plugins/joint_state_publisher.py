"""Gazebo's JointStatePublisher system (`gz-sim-joint-state-publisher-system`): gz.msgs.Model of joint states.

Parameters: `<joint_name>` (repeatable; default every moving joint), `<topic>` (default
/world/<world>/model/<model>/joint_state), `<update_rate>` Hz. Gazebo publishes on every physics step when
no rate is given; at 1 kHz that would be most of the sim's cost, so diffctl defaults to 50 Hz of sim time.
"""

from __future__ import annotations

from dataclasses import dataclass

from diffctl.bus import gz
from diffctl.description.model import Plugin
from diffctl.sim.entity import Entity
from diffctl.sim.plugins.base import PluginContext, SystemPlugin, float_param, rate_period_ns

DEFAULT_RATE_HZ = 50.0


@dataclass(frozen=True)
class JointStatePublisherParams:
    joint_names: tuple[str, ...]  # empty: every moving joint
    topic: str
    update_rate_hz: float

    @staticmethod
    def from_plugin(plugin: Plugin, world: str, model: str, source: str = "") -> JointStatePublisherParams:
        rate = float_param(plugin, "update_rate", DEFAULT_RATE_HZ, source=source, positive=True)
        return JointStatePublisherParams(
            joint_names=tuple(plugin.get_all("joint_name")),
            topic=plugin.get("topic") or f"/world/{world}/model/{model}/joint_state",
            update_rate_hz=rate or DEFAULT_RATE_HZ,
        )


class JointStatePublisher(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, plugin: Plugin) -> None:
        self.ctx, self.entity = ctx, entity
        self.params = JointStatePublisherParams.from_plugin(plugin, ctx.world_name, entity.name, entity.model.source)
        self.handles = [entity.joint(n) for n in self.params.joint_names or entity.joints]
        self.topic = self.params.topic
        self._pub = ctx.transport.publisher(self.topic, "gz.msgs.Model") if ctx.transport else None
        period = rate_period_ns(self.params.update_rate_hz, ctx.stepper.step_ns)
        self._task = ctx.stepper.add_task(f"joint_states:{entity.name}", period, self._publish)

    def message(self, sim_time_ns: int) -> dict:
        states = self.entity.joint_states(self.handles)
        return {
            "header": gz.header(sim_time_ns),
            "name": self.entity.name,
            "joint": [
                {"name": h.name, "axis1": {"position": p, "velocity": v, "force": e}}
                for h, (p, v, e) in zip(self.handles, states, strict=True)
            ],
        }

    def _publish(self, sim_time_ns: int) -> None:
        if self._pub is not None and self._pub.matched:
            self._pub.publish(self.message(sim_time_ns))

    def close(self) -> None:
        self.ctx.stepper.remove_task(self._task)
        if self._pub is not None and self.ctx.transport is not None:
            self.ctx.transport.release(self._pub)
