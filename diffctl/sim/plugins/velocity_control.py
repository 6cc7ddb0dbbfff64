"""Gazebo's VelocityControl system (`gz-sim-velocity-control-system`): a model (or links) moved at a set twist.

SDF parameters as gz-sim 8 reads them: `topic` (/model/<model>/cmd_vel, gz.msgs.Twist), `initial_linear` and
`initial_angular` (x y z), and `link_name` (repeatable; each link listens on /model/<model>/link/<link>/cmd_vel).
The twist is in the model's (a link's) own frame. Every step, from the step after a command arrives, the
physics sets the body's velocity to it, as gz-sim's physics does for a free group; the model is held at the
initial twist (zero by default) until then.
"""

from __future__ import annotations

import math
from typing import Any

import pybullet as pb

from diffctl.description.model import Plugin
from diffctl.description.pose import Vec3
from diffctl.errors import DescriptionError
from diffctl.sim.entity import Entity
from diffctl.sim.plugins.base import PluginContext, SystemPlugin
from diffctl.sim.plugins.system_support import valid_topic


def _vec3(plugin: Plugin, tag: str, source: str) -> Vec3:
    text = plugin.get(tag)
    if text is None:
        return (0.0, 0.0, 0.0)
    try:
        x, y, z = (float(v) for v in text.split())
    except ValueError:
        raise DescriptionError(
            f"plugin {plugin.name!r}: <{tag}> {text!r} is not three numbers",
            source=source or None,
            field=f"plugin {plugin.filename}: {tag}",
        ) from None
    return (x, y, z)


def _twist(fields: dict[str, Any]) -> tuple[Vec3, Vec3] | None:
    lin, ang = fields.get("linear") or {}, fields.get("angular") or {}
    out = tuple(tuple(float(v.get(k, 0.0) or 0.0) for k in "xyz") for v in (lin, ang))
    if not all(math.isfinite(c) for v in out for c in v):
        return None
    return out  # type: ignore[return-value]


class VelocityControl(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, plugin: Plugin) -> None:
        self.ctx, self.entity = ctx, entity
        source = entity.model.source
        self.initial = (_vec3(plugin, "initial_linear", source), _vec3(plugin, "initial_angular", source))
        self.model_twist: tuple[Vec3, Vec3] = self.initial
        self._pending: tuple[Vec3, Vec3] | None = None
        self.link_twists: dict[str, tuple[Vec3, Vec3]] = {}
        self._link_pending: dict[str, tuple[Vec3, Vec3]] = {}
        self.links = []
        for name in plugin.get_all("link_name"):
            if name in entity.plan.links:
                self.links.append(name)
            else:
                ctx.log.warn(f"VelocityControl: failed to find link [{name}] for model [{entity.name}]")
        self.topic = valid_topic(plugin.get("topic") or f"/model/{entity.name}/cmd_vel")
        self._subs = []
        t = ctx.transport
        if t is not None:
            self._subs.append(t.subscribe(self.topic, "gz.msgs.Twist", self.on_model_twist))
            for name in self.links:
                topic = valid_topic(f"/model/{entity.name}/link/{name}/cmd_vel")
                self._subs.append(t.subscribe(topic, "gz.msgs.Twist", lambda f, n=name: self.on_link_twist(n, f)))
        ctx.stepper.step_hooks.append(self._step)

    def on_model_twist(self, fields: dict[str, Any]) -> None:
        twist = _twist(fields)
        if twist is not None:
            self._pending = twist

    def on_link_twist(self, link: str, fields: dict[str, Any]) -> None:
        twist = _twist(fields)
        if twist is not None:
            self._link_pending[link] = twist

    def _step(self) -> None:
        canonical = self.entity.model.canonical_link or self.entity.model.root_link()
        self._set(canonical, self.model_twist, self.entity.pose().quat)
        for link, twist in self.link_twists.items():
            self._set(link, twist, self.entity.link_pose(link).quat)
        # gz-sim takes a command up after the step (PostUpdate) and applies it from the next one on
        if self._pending is not None:
            self.model_twist, self._pending = self._pending, None
        if self._link_pending:
            self.link_twists.update(self._link_pending)
            self._link_pending.clear()

    def _set(self, link: str, twist: tuple[Vec3, Vec3], frame_quat: tuple[float, float, float, float]) -> None:
        """Give the PyBullet body carrying `link` (its free group) this body-frame twist at its base."""
        body, _index, _ = self.entity.link_frame(link)
        cid = self.entity.client
        rot = pb.getMatrixFromQuaternion(frame_quat)
        lin_w = [sum(rot[3 * r + c] * twist[0][c] for c in range(3)) for r in range(3)]
        ang_w = [sum(rot[3 * r + c] * twist[1][c] for c in range(3)) for r in range(3)]
        # PyBullet's base velocity is its centre of mass's: add ω × (com − base link origin)
        com, _ = pb.getBasePositionAndOrientation(body, physicsClientId=cid)
        origin = self.entity.pb_link_pose(body, -1).xyz
        r = [com[i] - origin[i] for i in range(3)]
        lin_w = [
            lin_w[0] + ang_w[1] * r[2] - ang_w[2] * r[1],
            lin_w[1] + ang_w[2] * r[0] - ang_w[0] * r[2],
            lin_w[2] + ang_w[0] * r[1] - ang_w[1] * r[0],
        ]
        pb.resetBaseVelocity(body, lin_w, ang_w, physicsClientId=cid)

    def reset(self) -> None:
        self.model_twist, self._pending = self.initial, None
        self.link_twists.clear()
        self._link_pending.clear()

    def close(self) -> None:
        if self._step in self.ctx.stepper.step_hooks:
            self.ctx.stepper.step_hooks.remove(self._step)
        if self.ctx.transport is not None:
            for sub in self._subs:
                self.ctx.transport.release(sub)
