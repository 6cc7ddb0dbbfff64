"""gz_ros2_control/GazeboSimSystem: ros2_control hardware whose joints are the simulated model's joints.

It exists only inside the simulator, built by the gz_ros2_control plugin (gz_ros2_control.py) for the model
it is attached to, and called on the sim thread: `read` copies joint position and velocity into the state
interfaces (effort is exported but never updated, as gz_system.cpp does), `write` applies the claimed command
mode per joint (gz_ros2_control's `perform_command_mode_switch` bits):
  velocity → the joint's velocity target; position → a velocity P law v = -Kp (q - q_cmd) update_rate,
  recomputed every physics step; effort → a torque, reapplied every step; no active mode and
  `hold_joints` → velocity 0, otherwise the joint is free.
A command passes through as it is, as gz_system.cpp clamps nothing: joint limits (URDF `<limit>`, the interface's
min/max) bound commands in the controller manager's resource manager when its `enforce_command_limits` is true
(false in Jazzy; diffctl/control/joint_limits), never here; the joint's own SDF/URDF velocity and effort limits
still bound what the physics gets. NaN means "no command"; infinities never reach the physics.
"""

from __future__ import annotations

import math
from typing import Any

from diffctl.control.controller_interface import ReturnType
from diffctl.control.hardware_interface import HardwareComponent, HardwareInfo
from diffctl.errors import ConfigError, DescriptionError
from diffctl.sim.entity import Entity, JointHandle

PLUGIN_NAME = "gz_ros2_control/GazeboSimSystem"
PLUGIN_ALIASES = (PLUGIN_NAME, "ign_ros2_control/IgnitionSystem")
_MODES = ("velocity", "position", "effort")


class GazeboSimSystem(HardwareComponent):
    """Bound to a simulated entity with `bind` before the resource manager initialises it."""

    def __init__(self) -> None:
        super().__init__()
        self.entity: Entity | None = None
        self.hold_joints = True
        self.position_gain = 0.1
        self.handles: dict[str, JointHandle] = {}
        self.mode: dict[str, str | None] = {}
        self._per_step_joints: list[str] = []

    def bind(self, entity: Entity, *, hold_joints: bool, position_proportional_gain: float) -> GazeboSimSystem:
        self.entity = entity
        self.hold_joints = hold_joints
        self.position_gain = position_proportional_gain
        return self

    # --- lifecycle ----------------------------------------------------------------------------------
    def on_init(self, info: HardwareInfo) -> None:
        super().on_init(info)
        if self.entity is None:
            raise ConfigError(
                f"hardware {info.name!r} uses {info.plugin_name}, which runs only inside the simulator",
                source=info.source,
                hint="spawn the model (with its gz_ros2_control plugin) into `diffctl sim run`, or run this manager "
                "on mock hardware: --hardware-plugin mock_components/GenericSystem",
            )
        entity = self.entity
        for joint in info.joints:
            if joint.name not in entity.joints:
                # gz_ros2_control skips such a joint with a warning; an unknown joint is almost always a typo,
                # and a controller claiming it later would fail far from the cause: refuse it here.
                raise DescriptionError(
                    f"<ros2_control name={info.name!r}> joint {joint.name!r} is not a moving joint of model "
                    f"{entity.name!r}",
                    source=info.source,
                    hint=f"moving joints: {', '.join(entity.joints) or 'none'}",
                )
            self.handles[joint.name] = entity.joint(joint.name)
            self.mode[joint.name] = None
        self.reset_initial_states()

    def reset_initial_states(self) -> None:
        """state_interface initial_value seeds the joint (gz_ros2_control's JointPositionReset /
        JointVelocityReset, only for joints that have a command interface)."""
        assert self.entity is not None
        for joint in self.info.joints:
            if not joint.command_interfaces:
                continue
            h = self.handles[joint.name]
            for s in joint.state_interfaces:
                if s.initial_value is None:
                    continue
                if s.name == "position":
                    self.entity.reset_joint(h, position=s.initial_value)
                elif s.name == "velocity":
                    self.entity.reset_joint(h, velocity=s.initial_value)
        self._apply_idle()

    def export_state_interfaces(self) -> list[Any]:
        out = super().export_state_interfaces()
        for it in out:
            if math.isnan(it.value):
                it.value = 0.0
        self.read(0, 0.0)
        return out

    def export_command_interfaces(self) -> list[Any]:
        out = super().export_command_interfaces()
        # An initial_value on a state interface seeds the same-named command (gz_system.cpp).
        for joint in self.info.joints:
            for s in joint.state_interfaces:
                cmd = self.commands.get(f"{joint.name}/{s.name}")
                if cmd is not None and s.initial_value is not None and math.isnan(cmd.value):
                    cmd.value = s.initial_value
        return out

    def prepare_command_mode_switch(self, start: list[str], stop: list[str]) -> bool:
        per_joint: dict[str, int] = {}
        for name in start:
            joint, _, iface = name.rpartition("/")
            if iface in _MODES:
                per_joint[joint] = per_joint.get(joint, 0) + 1
        return all(n <= 1 for n in per_joint.values())

    def perform_command_mode_switch(self, start: list[str], stop: list[str]) -> bool:
        for name in stop:
            joint = name.rpartition("/")[0]
            if joint in self.mode:
                self.mode[joint] = None
        for name in start:
            joint, _, iface = name.rpartition("/")
            if joint in self.mode and iface in _MODES:
                self.mode[joint] = iface
        self._apply_idle()
        return True

    def on_deactivate(self) -> None:
        for joint in self.mode:
            self.mode[joint] = None
        self._apply_idle()

    def on_shutdown(self) -> None:
        self.on_deactivate()

    def on_error(self) -> None:
        self.on_deactivate()

    # --- real-time (sim thread) -----------------------------------------------------------------------
    def read(self, time_ns: int, period_s: float) -> ReturnType:
        assert self.entity is not None
        names = list(self.handles)
        for name, (pos, vel, _eff) in zip(names, self.entity.joint_states(list(self.handles.values())), strict=True):
            it = self.states.get(f"{name}/position")
            if it is not None:
                it.value = pos
            it = self.states.get(f"{name}/velocity")
            if it is not None:
                it.value = vel
        return ReturnType.OK

    def write(self, time_ns: int, period_s: float) -> ReturnType:
        """Apply velocity targets now; position and effort are reapplied every physics step by `step`."""
        assert self.entity is not None
        per_step = []
        for joint, mode in self.mode.items():
            value = self._command(joint, mode)
            h = self.handles[joint]
            if h.joint.mimic is not None:
                # gz_ros2_control overwrites a mimic joint's command with its mimic servo; here the physics holds
                # it to its leader (sim/mimic.py), so it is neither commanded nor held.
                self.entity.release_joint(h)
            elif mode == "velocity" and value is not None:
                self.entity.set_joint_velocity(h, value)
            elif mode in ("position", "effort") and value is not None:
                per_step.append(joint)
            elif self.hold_joints:
                self.entity.set_joint_velocity(h, 0.0)
            else:
                self.entity.release_joint(h)
        self._per_step_joints = per_step
        self.step()
        return ReturnType.OK

    @property
    def steps(self) -> bool:
        """Whether `step` has work on every physics step (a joint commanded in position or effort)."""
        return bool(self._per_step_joints)

    def step(self) -> None:
        """Per physics step: the position P law and efforts need the current state or a fresh torque."""
        if not self._per_step_joints:
            return
        assert self.entity is not None
        rate = float(self.update_rate or 100)
        for joint in self._per_step_joints:
            mode = self.mode[joint]
            value = self._command(joint, mode)
            h = self.handles[joint]
            if value is None:
                continue
            if mode == "position":
                q = self.entity.joint_states([h])[0][0]
                self.entity.set_joint_velocity(h, -self.position_gain * (q - value) * rate)
            elif mode == "effort":
                self.entity.set_joint_effort(h, value)

    def _command(self, joint: str, mode: str | None) -> float | None:
        if mode is None:
            return None
        cmd = self.commands.get(f"{joint}/{mode}")
        if cmd is None or not math.isfinite(cmd.value):
            return None  # NaN: no command (held); inf never reaches the physics
        return cmd.value

    def _apply_idle(self) -> None:
        if self.entity is None:
            return
        for joint, mode in self.mode.items():
            if mode is None:
                h = self.handles[joint]
                if self.hold_joints and h.joint.mimic is None:
                    self.entity.set_joint_velocity(h, 0.0)
                else:
                    self.entity.release_joint(h)
