"""The gz_ros2_control system: a hardware endpoint a controller manager attaches to, in lockstep on sim time.

Protocol and keys: diffctl/bus/hw_endpoint.py. The sim side, following gz_ros2_control (ros2_control.md §4):
- the endpoint exists (liveliness token) for a model whose SDF has the gz_ros2_control plugin and a
  <ros2_control> block with gz_ros2_control/GazeboSimSystem hardware; `info` describes its joints;
- `attach` (from the manager, with its update_rate) fixes the control period; from then on, every period of
  sim time, the sim publishes the joint states for tick n and does not step on until the command for tick n
  arrives (lockstep), so results do not depend on machine speed;
- a command missing after DEADLINE_S of wall time is counted (stats: lockstep overruns) and logged, and the
  joints are held (the first command after an attach gets ATTACH_GRACE_S: the manager attaches when its
  hardware activates and starts its loop after that, which a loaded machine can stretch past a second);
  when the manager's liveliness token goes away the sim detaches and runs on, joints held;
- commands apply on every physics step until the next: velocity as a motor target, position through
  gz_ros2_control's P law (v = -Kp (q - q_cmd) update_rate), effort as a torque; joints with no command are
  held (velocity 0) when <hold_joints> is true (the default), else free.
"""

from __future__ import annotations

import math
import queue
import time
from dataclasses import dataclass
from typing import Any

import numpy as np
import pybullet as pb
import zenoh

from diffctl.bus import hw_endpoint as hw
from diffctl.description.model import Plugin, Ros2Control
from diffctl.errors import DescriptionError
from diffctl.sim.entity import Entity, JointHandle
from diffctl.sim.plugins.base import PluginContext, SystemPlugin, bool_param, float_param

DEADLINE_S = 1.0
ATTACH_GRACE_S = 10.0  # a manager that dies meanwhile is noticed at once, through its liveliness token
HARDWARE = "gz_ros2_control/GazeboSimSystem"
_GONE = object()


@dataclass(frozen=True)
class GzRos2ControlParams:
    """The gz_ros2_control plugin's own parameters that matter to the simulator side."""

    parameters: tuple[str, ...]  # the controller manager's YAML files (read by the manager, not the sim)
    hold_joints: bool
    position_proportional_gain: float

    @staticmethod
    def from_plugin(plugin: Plugin, source: str = "") -> GzRos2ControlParams:
        return GzRos2ControlParams(
            parameters=tuple(plugin.get_all("parameters")),
            hold_joints=bool_param(plugin, "hold_joints", True, source=source),
            position_proportional_gain=float_param(plugin, "position_proportional_gain", 0.1, source=source) or 0.1,
        )


def gazebo_block(entity: Entity) -> Ros2Control | None:
    for block in entity.model.ros2_control:
        if block.hardware_plugin == HARDWARE:
            return block
    return None


class Ros2ControlEndpoint(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, plugin: Plugin, block: Ros2Control) -> None:
        self.ctx, self.entity, self.block = ctx, entity, block
        self.model = entity.name
        self.handles: list[JointHandle] = []
        for j in block.joints:
            if j.name not in entity.joints:
                raise DescriptionError(
                    f"<ros2_control> joint {j.name!r} is not a moving joint of model {self.model!r}",
                    source=entity.model.source or None,
                    field=f"ros2_control {block.name}",
                    hint=f"moving joints: {', '.join(entity.joints) or 'none'}",
                )
            self.handles.append(entity.joint(j.name))
        self.params = GzRos2ControlParams.from_plugin(plugin, entity.model.source)
        self.hold = self.params.hold_joints
        self.kp = self.params.position_proportional_gain
        n = len(self.handles)
        self.vel_cmd = np.full(n, np.nan)
        self.pos_cmd = np.full(n, np.nan)
        self.eff_cmd = np.full(n, np.nan)
        self.tick = 0
        self._first_command = False  # waiting for a newly attached manager's first command
        self.manager: str | None = None
        self.update_rate = 0.0
        self.period_ns = 0
        self.overruns = 0
        self._task = None
        self._hooked = False
        self._inbox: queue.SimpleQueue = queue.SimpleQueue()
        self._initial_states()
        self._state_pub = None
        self._declared: list[Any] = []
        t = ctx.transport
        if t is not None:
            self._state_pub = t.raw_publisher(hw.state_key(self.model))
            self._declared = [
                self._state_pub,
                t.raw_subscribe(hw.command_key(self.model), self._on_command),
                t.liveliness_subscriber(hw.manager_key(self.model), self._on_manager_token),
                # Answered on the Zenoh thread: read-only, and it must answer while the sim waits in lockstep.
                t.direct_service(hw.info_key(self.model), self.info),
                t.service(hw.attach_key(self.model), lambda req, reply: self._on_attach(req), fast=self._refuse),
                # Last: a manager that sees the token finds everything above already in place.
                t.token(hw.endpoint_key(self.model)),
            ]
        ctx.log.info(f"ros2_control endpoint for model {self.model!r}: joints {', '.join(self.joint_names)}")

    @property
    def joint_names(self) -> list[str]:
        return [h.name for h in self.handles]

    def _initial_states(self) -> None:
        """Honour state interfaces' initial_value (gz_ros2_control resets the joint to it), then hold."""
        for h, j in zip(self.handles, self.block.joints, strict=True):
            for s in j.state_interfaces:
                if s.initial_value is not None and s.name == "position":
                    pb.resetJointState(h.body, h.index, s.initial_value, physicsClientId=self.entity.client)
        self._apply()

    # --- protocol ------------------------------------------------------------------------------------

    def info(self) -> dict[str, Any]:
        joints = []
        for j in self.block.joints:
            joints.append(
                {
                    "name": j.name,
                    "command_interfaces": [c.name for c in j.command_interfaces],
                    "state_interfaces": [s.name for s in j.state_interfaces],
                    "initial": {s.name: s.initial_value for s in j.state_interfaces if s.initial_value is not None},
                }
            )
        return {
            "model": self.model,
            "joints": joints,
            "physics_step_s": self.ctx.stepper.step_ns * 1e-9,
            "sim_time_ns": self.ctx.stepper.sim_time_ns,
            "manager": self.manager,
            "lockstep_overruns": self.overruns,
        }

    def _refuse(self, req: dict[str, Any]) -> dict[str, Any] | None:
        """The reasons to refuse an attach request, checked at once on the Zenoh thread."""
        rate = req.get("update_rate")
        manager = str(req.get("manager") or "")
        if not isinstance(rate, int | float) or isinstance(rate, bool) or not math.isfinite(rate) or rate <= 0:
            return {"ok": False, "error": f"update_rate {rate!r} must be a positive number of Hz"}
        current = self.manager
        if current is not None and manager != current:
            return {"ok": False, "error": f"model {self.model!r} is already controlled by manager {current!r}"}
        return None

    def _on_attach(self, req: dict[str, Any]) -> dict[str, Any]:
        refused = self._refuse(req)
        return refused or self.attach(float(req["update_rate"]), str(req.get("manager") or ""))

    def attach(self, update_rate: float, manager: str) -> dict[str, Any]:
        """Start lockstep with a manager at `update_rate` Hz (sim thread)."""
        step_ns = self.ctx.stepper.step_ns
        period = max(step_ns, round(1e9 / update_rate))
        if round(1e9 / update_rate) < step_ns:
            self.ctx.log.warn(
                f"ros2_control update_rate {update_rate:g} Hz is faster than the physics step "
                f"({step_ns * 1e-6:g} ms): the controller runs once per step"
            )
        self._drain()
        self.manager, self.update_rate, self.period_ns = manager, update_rate, period
        self._first_command = True
        if self._task is not None:
            self.ctx.stepper.remove_task(self._task)
        # The first exchange happens after the next step; ticks continue from the last one sent.
        self._task = self.ctx.stepper.add_task(
            f"ros2_control:{self.model}",
            period,
            self._exchange,
            first_ns=self.ctx.stepper.sim_time_ns + step_ns,
            before_others=True,
        )
        self.ctx.log.info(f"controller manager {manager!r} attached to {self.model!r} at {update_rate:g} Hz")
        return {"ok": True, "next_tick": self.tick, "control_period_ns": period}

    def detach(self, why: str) -> None:
        if self.manager is None:
            return
        self.ctx.log.warn(f"controller manager {self.manager!r} left model {self.model!r} ({why}); joints held")
        self.manager = None
        if self._task is not None:
            self.ctx.stepper.remove_task(self._task)
            self._task = None
        self.hold_all()

    def _exchange(self, sim_time_ns: int) -> None:
        """One control period: publish state for this tick first, then (once the sensors and clock due now
        have done their work, while the manager computes) wait for its command and apply it."""
        tick = self.tick
        self.tick += 1
        if self._state_pub is not None:
            states = self.entity.joint_states(self.handles)
            pos = [s[0] for s in states]
            vel = [s[1] for s in states]
            eff = [s[2] for s in states]
            self._state_pub.put(hw.encode_state(tick, sim_time_ns, pos, vel, eff))
        if self.manager is not None:
            self.ctx.stepper.later_this_step(lambda: self._await_command(tick))

    def _await_command(self, tick: int) -> None:
        if self.manager is None:
            return
        t0 = time.perf_counter()
        wait_s = ATTACH_GRACE_S if self._first_command else DEADLINE_S
        deadline = t0 + wait_s
        while True:
            remaining = deadline - time.perf_counter()
            try:
                item = self._inbox.get(timeout=max(0.0, remaining))
            except queue.Empty:
                self.overruns += 1
                self.ctx.stepper.stats.lockstep_overruns += 1
                self.ctx.log.warn(
                    f"ros2_control {self.model!r}: no command for tick {tick} within {wait_s:g} s "
                    f"(lockstep overrun {self.overruns}); joints held"
                )
                self.hold_all()
                self._first_command = False
                break
            if item is _GONE:
                if self._manager_alive():
                    continue  # a re-attaching manager replaced its token
                self.detach("its liveliness token disappeared")
                break
            if item.tick == tick:
                self.set_commands(item.velocity, item.position, item.effort)
                self._first_command = False
                break
            # A command for an older tick (answered after its deadline): skip it.
        self.ctx.stepper.stats.idle_s += time.perf_counter() - t0

    # --- Zenoh threads ------------------------------------------------------------------------------

    def _on_command(self, sample: Any) -> None:
        try:
            cmd = hw.decode_command(sample.payload.to_bytes())
        except Exception as e:
            self.ctx.log.throttled(f"badcmd:{self.model}", f"ros2_control {self.model!r}: dropped a command: {e}")
            return
        if len(cmd.velocity) != len(self.handles):
            self.ctx.log.throttled(
                f"badcmd:{self.model}",
                f"ros2_control {self.model!r}: command for {len(cmd.velocity)} joints, expected {len(self.handles)}",
            )
            return
        self._inbox.put(cmd)

    def _on_manager_token(self, sample: Any) -> None:
        if sample.kind == zenoh.SampleKind.DELETE:
            self._inbox.put(_GONE)
            # When the sim is not waiting (paused, or between ticks), detach on the sim thread too.
            self.ctx.stepper.call_soon(self._check_gone)

    def _check_gone(self) -> None:
        items = []
        gone = False
        while True:
            try:
                item = self._inbox.get_nowait()
            except queue.Empty:
                break
            if item is _GONE:
                gone = True
            else:
                items.append(item)
        for it in items:
            self._inbox.put(it)
        if gone and not self._manager_alive():
            self.detach("its liveliness token disappeared")

    def _manager_alive(self) -> bool:
        """Whether some manager token for this model exists (a manager re-attaching swaps its token)."""
        t = self.ctx.transport
        if t is None:
            return False
        try:
            return any(r.ok is not None for r in t.session.liveliness().get(hw.manager_key(self.model), timeout=0.3))
        except Exception:
            return False

    def _drain(self) -> None:
        while True:
            try:
                self._inbox.get_nowait()
            except queue.Empty:
                return

    # --- applying commands ----------------------------------------------------------------------------

    def set_commands(self, vel: Any, pos: Any, eff: Any) -> None:
        self.vel_cmd = np.asarray(vel, dtype=np.float64).copy()
        self.pos_cmd = np.asarray(pos, dtype=np.float64).copy()
        self.eff_cmd = np.asarray(eff, dtype=np.float64).copy()
        self._apply()

    def hold_all(self) -> None:
        n = len(self.handles)
        self.set_commands(np.full(n, np.nan), np.full(n, np.nan), np.full(n, np.nan))

    def _apply(self) -> None:
        per_step = False
        for i, h in enumerate(self.handles):
            if math.isfinite(self.vel_cmd[i]):
                self.entity.set_joint_velocity(h, float(self.vel_cmd[i]))
            elif math.isfinite(self.pos_cmd[i]) or math.isfinite(self.eff_cmd[i]):
                per_step = True
            elif self.hold:
                self.entity.set_joint_velocity(h, 0.0)
            else:
                self.entity.release_joint(h)
        if per_step and not self._hooked:
            self.ctx.stepper.step_hooks.append(self._per_step)
            self._hooked = True
        elif not per_step and self._hooked:
            self.ctx.stepper.step_hooks.remove(self._per_step)
            self._hooked = False

    def _per_step(self) -> None:
        # Position and effort commands need the current joint state (or a fresh torque) every step.
        rate = self.update_rate or 1.0 / (self.ctx.stepper.step_ns * 1e-9)
        for i, h in enumerate(self.handles):
            if math.isfinite(self.vel_cmd[i]):
                continue
            if math.isfinite(self.pos_cmd[i]):
                q = self.entity.joint_states([h])[0][0]
                self.entity.set_joint_velocity(h, -self.kp * (q - float(self.pos_cmd[i])) * rate)
            elif math.isfinite(self.eff_cmd[i]):
                self.entity.set_joint_effort(h, float(self.eff_cmd[i]))

    def reset(self) -> None:
        self.hold_all()
        self._initial_states()

    def close(self) -> None:
        if self._task is not None:
            self.ctx.stepper.remove_task(self._task)
        if self._hooked:
            self.ctx.stepper.step_hooks.remove(self._per_step)
            self._hooked = False
        if self.ctx.transport is not None:
            for obj in reversed(self._declared):
                self.ctx.transport.release(obj)
            self._declared = []
