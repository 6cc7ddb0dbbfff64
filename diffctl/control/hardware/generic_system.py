"""mock_components/GenericSystem: hardware that mirrors commands to states, or integrates them.

Hardware `<param>`s, as in ros2_control's mock components:
  calculate_dynamics (false)   false: a position command sets the position state (+ offset); any other
                               command is mirrored to the state of the same name. true: the claimed
                               command (position, velocity or acceleration; one per joint) is integrated
                               into position/velocity/acceleration states, backward as upstream (position
                               advances by the previous velocity); other commands are mirrored.
  position_state_following_offset (0.0) is added to the position state (in velocity and acceleration
                               mode on every step, as upstream); with custom_interface_with_following_offset
                               ("") it goes to that interface instead: its state = position command + offset.
  disable_commands (false)     states never follow commands (warned about, throttled)
  mock_sensor_commands, mock_gpio_commands (false)  command interfaces for sensor/GPIO states, mirrored.
States start at their `initial_value` or 0.0 at configure; commands start as NaN (no command).
A NaN command is ignored; an infinite one makes read() return ERROR. A joint with `<param name="mimic">`
(and optional `multiplier`) copies every state of the mimicked joint, scaled.
Behaviour read from ros2_control's hardware_interface/src/mock_components/generic_system.cpp (commit 03bf04b).
"""

from __future__ import annotations

import math
import time
from typing import Any

from diffctl.control.controller_interface import CommandInterface, ReturnType, StateInterface
from diffctl.control.hardware_interface import HardwareComponent, HardwareInfo
from diffctl.errors import ParameterError

_MODES = ("position", "velocity", "acceleration")
_INFINITE = (math.inf, -math.inf)
_OK = ReturnType.OK
_BOOL = {"true": True, "false": False, "1": True, "0": False}


def _bool_param(info: HardwareInfo, key: str) -> bool:
    raw = info.hardware_parameters.get(key, "false")
    val = _BOOL.get(str(raw).strip().lower())
    if val is None:
        raise ParameterError(
            f"{raw!r} is not a bool (true or false)",
            source=info.source,
            field=f"<ros2_control name={info.name!r}>/hardware/param[{key}]",
        )
    return val


def _float_param(info: HardwareInfo, key: str) -> float:
    raw = info.hardware_parameters.get(key, "0.0")
    try:
        val = float(raw)
    except ValueError:
        val = math.nan
    if not math.isfinite(val):
        raise ParameterError(
            f"{raw!r} is not a finite number",
            source=info.source,
            field=f"<ros2_control name={info.name!r}>/hardware/param[{key}]",
        )
    return val


class GenericSystem(HardwareComponent):
    def on_init(self, info: HardwareInfo) -> None:
        super().on_init(info)
        self.calculate_dynamics = _bool_param(info, "calculate_dynamics")
        self.disable_commands = _bool_param(info, "disable_commands")
        self.mock_sensor_commands = _bool_param(info, "mock_sensor_commands")
        self.mock_gpio_commands = _bool_param(info, "mock_gpio_commands")
        self.offset = _float_param(info, "position_state_following_offset")
        self.custom_offset_interface = info.hardware_parameters.get("custom_interface_with_following_offset", "")
        self._mode: dict[str, str | None] = {j.name: None for j in info.joints}
        self._cached_plan: _Plan | None = None
        self._last_warn = 0.0
        for j in info.joints:
            names = [c.name for c in j.command_interfaces]
            if self.calculate_dynamics and any(n not in _MODES for n in names):
                bad = [n for n in names if n not in _MODES]
                raise ParameterError(
                    f"with calculate_dynamics, command interfaces must be among {_MODES}; joint {j.name!r} has {bad}",
                    source=info.source,
                )
        # <joint><param name="mimic">other</param><param name="multiplier">k</param>: every state = k × other's.
        names = {j.name for j in info.joints}
        self._joint_interfaces = {j.name: [it.name for it in j.state_interfaces] for j in info.joints}
        self._mimics: list[tuple[str, str, float]] = []
        for j in info.joints:
            mimicked = j.parameters.get("mimic")
            if mimicked is None:
                continue
            if mimicked not in names:
                raise ParameterError(
                    f"mimicked joint {mimicked!r} not found (joints: {sorted(names)})",
                    source=info.source,
                    field=f"<ros2_control name={info.name!r}>/joint[{j.name}]/param[mimic]",
                )
            raw = j.parameters.get("multiplier", "1.0")
            try:
                multiplier = float(raw)
            except ValueError:
                multiplier = math.nan
            if not math.isfinite(multiplier):
                raise ParameterError(
                    f"{raw!r} is not a finite number",
                    source=info.source,
                    field=f"<ros2_control name={info.name!r}>/joint[{j.name}]/param[multiplier]",
                )
            self._mimics.append((j.name, mimicked, multiplier))
        self._initial: dict[str, float] = {}
        for comp in info.components:
            for it in comp.state_interfaces:
                self._initial[f"{comp.name}/{it.name}"] = 0.0 if it.initial_value is None else it.initial_value

    def export_command_interfaces(self) -> list[CommandInterface]:
        out = super().export_command_interfaces()
        extra = ((self.info.sensors, self.mock_sensor_commands), (self.info.gpios, self.mock_gpio_commands))
        for comps, enabled in extra:
            if not enabled:
                continue
            for comp in comps:
                for it in comp.state_interfaces:
                    name = f"{comp.name}/{it.name}"
                    if name not in self.commands:
                        self.commands[name] = CommandInterface(name, math.nan)
                        out.append(self.commands[name])
        self._cached_plan = None
        return out

    def export_state_interfaces(self) -> list[StateInterface]:
        out = super().export_state_interfaces()
        for it in out:
            it.value = self._initial.get(it.name, 0.0)
        self._cached_plan = None
        return out

    def on_configure(self) -> None:
        for name, st in self.states.items():
            st.value = self._initial.get(name, 0.0)
        for c in self.commands.values():
            c.value = math.nan

    # --- command modes (only meaningful with calculate_dynamics) --------------------------------------
    def prepare_command_mode_switch(self, start: list[str], stop: list[str]) -> bool:
        if not self.calculate_dynamics:
            return True
        per_joint: dict[str, int] = {}
        for name in start:
            joint, _, iface = name.rpartition("/")
            if joint in self._mode and iface in _MODES:
                per_joint[joint] = per_joint.get(joint, 0) + 1
        bad = [j for j, n in per_joint.items() if n > 1]
        if bad and self.log is not None:
            self.log.error(f"{self.name}: only one command mode per joint with calculate_dynamics; {bad} got several")
        return not bad

    def perform_command_mode_switch(self, start: list[str], stop: list[str]) -> bool:
        for name in stop:
            joint = name.rpartition("/")[0]
            if joint in self._mode:
                self._mode[joint] = None
        for name in start:
            joint, _, iface = name.rpartition("/")
            if joint in self._mode and iface in _MODES:
                self._mode[joint] = iface
        self._cached_plan = None
        return True

    # --- real-time ---------------------------------------------------------------------------------------
    def _plan(self) -> _Plan:
        """The handles read() walks, resolved from names once: rebuilt when the handles or the modes change."""
        plan = self._cached_plan
        if plan is None:
            plan = self._cached_plan = _Plan(self)
        return plan

    def read(self, time_ns: int, period_s: float) -> ReturnType:
        if self.disable_commands:
            now = time.monotonic()
            if self.log is not None and now - self._last_warn > 10.0:
                self._last_warn = now
                self.log.warn(f"{self.name}: Command propagation is disabled - no values will be returned!")
            return ReturnType.OK
        # One tuple, its empty parts None: a cycle touches no object it has nothing to do with.
        commands, by_velocity, integrate, mirror, custom_offset, mimics, position_offset = (
            self._cached_plan or self._plan()).steps
        for c in commands:
            v = c.value
            if v in _INFINITE:
                if self.log is not None:
                    self.log.error(f"{self.name}: command {c.name} is {v}")
                return ReturnType.ERROR
        dt = period_s
        if by_velocity and dt > 0.0:
            # Velocity-commanded joints (a wheel), the mock's dynamics written for that mode alone: position
            # advances by the previous velocity, the command becomes the velocity, the change the acceleration
            # (when the joint has that state).
            for command, pos_s, vel_s, acc_s in by_velocity:
                cmd = command.value
                vel = vel_s.value
                pos_s.value += vel * dt + position_offset
                if cmd == cmd:
                    if acc_s is not None:
                        acc_s.value = (cmd - vel) / dt
                    vel_s.value = cmd
        if integrate and dt > 0.0:
            # The position- and acceleration-commanded joints (backward integration as above).
            for mode, command, pos_s, vel_s, acc_s in integrate:
                cmd = command.value
                pos = pos_s.value
                vel = vel_s.value
                acc = acc_s.value
                if mode == "acceleration":
                    pos += vel * dt + position_offset
                    vel += acc * dt
                    if cmd == cmd:
                        acc = cmd
                elif cmd == cmd:  # position
                    new_pos = cmd + position_offset
                    new_vel = (new_pos - pos) / dt
                    acc = (new_vel - vel) / dt
                    pos, vel = new_pos, new_vel
                pos_s.value = pos
                vel_s.value = vel
                acc_s.value = acc
        # Commands mirrored to the state of the same name (a NaN command is no command), in the commands' order.
        if mirror:
            for cmd, st, offset in mirror:
                v = cmd.value
                if v == v:
                    st.value = v if offset is None else v + offset
        if custom_offset:
            for cmd, target in custom_offset:
                v = cmd.value
                if v == v:
                    target.value = v + self.offset
        if mimics:
            for dst, src, multiplier in mimics:
                dst.value = multiplier * src.value
        return _OK

    def write(self, time_ns: int, period_s: float) -> ReturnType:
        return ReturnType.OK

    # Nothing to write: the manager's cycle skips the call (a subclass that writes overrides the function, and
    # its function carries no such mark).
    write.writes_nothing = True  # type: ignore[attr-defined]


class _Missing:
    """Stands in for a state interface a joint does not have: reads 0.0, ignores writes (as upstream)."""

    __slots__ = ()

    @property
    def value(self) -> float:
        return 0.0

    @value.setter
    def value(self, _v: float) -> None:
        pass


_MISSING = _Missing()


class _Plan:
    """GenericSystem.read()'s work as lists of handles, so a cycle builds no names and looks up no tables."""

    def __init__(self, hw: GenericSystem) -> None:
        states, commands = hw.states, hw.commands
        calc = hw.calculate_dynamics
        self.commands = list(commands.values())
        # The position offset goes to the custom interface when one is named, else to the position state.
        self.position_offset = 0.0 if hw.custom_offset_interface else hw.offset
        self.integrate: list[tuple[str, CommandInterface, Any, Any, Any]] = []
        # (command, position, velocity, acceleration or None): the velocity-commanded joints, apart
        self.by_velocity: list[tuple[CommandInterface, Any, Any, Any]] = []
        if calc:
            for joint, mode in hw._mode.items():
                if mode is None:
                    continue
                pos_s, vel_s, acc_s = (states.get(f"{joint}/{k}") or _MISSING for k in _MODES)
                if mode == "velocity":
                    self.by_velocity.append((commands[f"{joint}/{mode}"], pos_s, vel_s,
                                             None if acc_s is _MISSING else acc_s))
                else:
                    self.integrate.append((mode, commands[f"{joint}/{mode}"], pos_s, vel_s, acc_s))
        # (command, state, offset added or None): a joint's mode interfaces (with calculate_dynamics) are the
        # integrator's, a position command without it sets the position state plus the offset.
        self.mirror: list[tuple[CommandInterface, StateInterface, float | None]] = []
        for name, cmd in commands.items():
            joint, _, iface = name.rpartition("/")
            st = states.get(name)
            if iface in (_MODES if calc else ("position",)) and joint in hw._mode:
                if iface == "position" and not calc and st is not None:
                    self.mirror.append((cmd, st, self.position_offset))
                continue
            if st is not None:
                self.mirror.append((cmd, st, None))
        self.custom_offset: list[tuple[CommandInterface, StateInterface]] = []
        if hw.custom_offset_interface:
            for joint in hw._mode:
                cmd = commands.get(f"{joint}/position")
                target = states.get(f"{joint}/{hw.custom_offset_interface}")
                if cmd is not None and target is not None:
                    self.custom_offset.append((cmd, target))
        self.mimics: list[tuple[StateInterface, StateInterface, float]] = []
        for joint, mimicked, multiplier in hw._mimics:
            for iface in hw._joint_interfaces[joint]:
                src = states.get(f"{mimicked}/{iface}")
                if src is not None:
                    self.mimics.append((states[f"{joint}/{iface}"], src, multiplier))
        # What read() takes, in one tuple; the empty parts None.
        self.steps = (tuple(self.commands), *(tuple(part) or None for part in (
            self.by_velocity, self.integrate, self.mirror, self.custom_offset, self.mimics)), self.position_offset)
