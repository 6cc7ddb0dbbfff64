"""Gazebo's ApplyJointForce system (`gz-sim-apply-joint-force-system`): a joint effort held until the next one.

SDF parameter: `joint_name`. The effort arrives as gz.msgs.Double on /model/<model>/joint/<joint>/cmd_force and
is added to the joint's effort in every step (together with what other systems command there).
"""

from __future__ import annotations

import math
from typing import Any

from diffctl.description.model import Plugin
from diffctl.sim.entity import Entity
from diffctl.sim.plugins.base import PluginContext, SystemPlugin
from diffctl.sim.plugins.system_support import find_joints, valid_topic


class ApplyJointForce(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, plugin: Plugin) -> None:
        self.ctx, self.entity = ctx, entity
        name = (plugin.get("joint_name") or "").strip()
        self.joints = find_joints(ctx, entity, [name], "ApplyJointForce") if name else []
        self.effort = 0.0
        self._sub = None
        if not name:
            ctx.log.warn(f"ApplyJointForce on model {entity.name!r} found an empty joint_name: not started")
            return
        self.topic = valid_topic(f"/model/{entity.name}/joint/{name}/cmd_force")
        if ctx.transport is not None:
            self._sub = ctx.transport.subscribe(self.topic, "gz.msgs.Double", self.on_force)
        if self.joints:
            ctx.stepper.step_hooks.append(self._step)

    def on_force(self, fields: dict[str, Any]) -> None:
        value = float(fields.get("data", 0.0) or 0.0)
        if math.isfinite(value):
            self.effort = value

    def _step(self) -> None:
        if self.effort:
            self.entity.add_joint_effort(self.joints[0], self.effort)

    def reset(self) -> None:
        self.effort = 0.0

    def close(self) -> None:
        if self._step in self.ctx.stepper.step_hooks:
            self.ctx.stepper.step_hooks.remove(self._step)
        if self._sub is not None and self.ctx.transport is not None:
            self.ctx.transport.release(self._sub)
