"""Hardware components, their lifecycle, and the registry of interfaces loaned to controllers.

As in hardware_interface::ResourceManager: state interfaces are available while their component is
inactive or active and may be shared; command interfaces are available only while it is active and are
claimed by at most one controller. read() runs on inactive and active components, write() on active ones;
a component whose read or write returns ERROR (or raises) is reported so the manager can deactivate the
controllers that use it, and it goes to unconfigured.

Reference interfaces of chainable controllers (`<controller>/linear/velocity`) are command interfaces too,
owned by that controller instead of a component: imported when it is configured, available while it is
active, claimed like any other by the controller chained in front of it, removed at cleanup. The state
interfaces a chainable controller exports are state interfaces owned the same way (shared, never claimed).

Joint limits (the manager's `enforce_command_limits`): `import_joint_limiters` gives joints a limiter
(diffctl/control/joint_limits); `limit_command` bounds one command as its controller writes it, and
`enforce_command_limits` bounds every joint's claimed commands at once before the hardware writes them, both
from the joint's state interfaces and the limiter's previous command, which every command-mode switch forgets.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

from diffctl.control.controller_interface import CommandInterface, ReturnType, StateInterface
from diffctl.control.hardware_interface import HardwareComponent, HardwareInfo
from diffctl.control.joint_limits.joint_limits import INTERFACE_KINDS, JointControlInterfacesData, limiter_data_string
from diffctl.control.joint_limits.joint_limits_urdf import JointLimiterSpec
from diffctl.control.joint_limits.joint_saturation_limiter import JointSaturationLimiter
from diffctl.control.joint_limits.joint_soft_limiter import JointSoftLimiter
from diffctl.control.lifecycle import State, TransitionError, hook_message
from diffctl.control.plugin_registry import hardware_for
from diffctl.errors import ConfigError, DiffctlError


@dataclass(eq=False)
class HardwareHandle:
    name: str
    info: HardwareInfo
    component: HardwareComponent
    state: State = State.UNCONFIGURED
    states: list[StateInterface] = field(default_factory=list)
    commands: list[CommandInterface] = field(default_factory=list)
    rw_rate: int = 0
    last_rw_ns: int | None = None
    read_errors: int = 0
    write_errors: int = 0
    due: bool = True
    rw_period_s: float = 0.0

    @property
    def plugin_name(self) -> str:
        return self.info.plugin_name


@dataclass(eq=False)
class JointLimiterEntry:
    """A joint's limiter and the interfaces it reads and bounds ("joint/position", …: those that exist)."""

    hardware: str
    joint: str
    limiter: JointSaturationLimiter
    states: tuple[tuple[str, StateInterface], ...] = ()
    commands: tuple[tuple[str, CommandInterface], ...] = ()

    def actual(self) -> JointControlInterfacesData:
        data = JointControlInterfacesData(self.joint)
        for kind, handle in self.states:
            setattr(data, kind, handle.value)
        return data


# A controller's claimed command interface that a joint limiter bounds: (its handle, the limiter, the interface kind)
LimitedCommand = tuple[CommandInterface, JointLimiterEntry, str]


class ResourceManager:
    def __init__(self, log: Callable[[str], None] | None = None) -> None:
        self.components: dict[str, HardwareHandle] = {}
        self.state_interfaces: dict[str, StateInterface] = {}
        self.command_interfaces: dict[str, CommandInterface] = {}
        self.owner: dict[str, str] = {}  # interface name → component name
        self.claimed: dict[str, str] = {}  # command interface → controller name
        self.reference_owner: dict[str, str] = {}  # reference interface → the controller exporting it
        self.exported_state_owner: dict[str, str] = {}  # a controller's exported state interface → it
        self._reference_available: set[str] = set()  # the exported interfaces of active controllers
        self._warn = log or (lambda _t: None)
        self._active: tuple[HardwareHandle, ...] = ()
        self._readable: tuple[HardwareHandle, ...] = ()
        self._slow_active = self._slow_readable = False
        self.single: tuple[HardwareHandle, Callable, Callable | None] | None = None
        self.joint_limiters: dict[str, JointLimiterEntry] = {}  # by joint name
        self._limits_log: Any = None
        self._limits_logged_s = -math.inf  # monotonic time of the last "out of limits" error
        # each limited joint with its claimed commands; None: to be worked out again (claims changed)
        self._limited_claims: tuple[tuple[JointLimiterEntry, tuple[tuple[str, CommandInterface], ...]], ...] | None
        self._limited_claims = ()

    # --- loading ---------------------------------------------------------------------------------------
    def load(
        self,
        info: HardwareInfo,
        logger: object | None = None,
        update_rate: int = 0,
        cancel: object | None = None,
        component: HardwareComponent | None = None,
    ) -> HardwareHandle:
        """Initialise `info`'s hardware: an instance of its registered plugin, or `component` when the host
        built it already (the simulator binds GazeboSimSystem to its model's joints)."""
        if info.name in self.components:
            raise ConfigError(f"two <ros2_control> blocks are named {info.name!r}", source=info.source)
        comp = component if component is not None else hardware_for(info)()
        comp.log = logger
        comp.update_rate = update_rate
        comp.cancel = cancel
        try:
            comp.on_init(info)
            states = list(comp.export_state_interfaces())
            commands = list(comp.export_command_interfaces())
        except DiffctlError:
            raise
        except Exception as e:
            raise ConfigError(
                f"hardware {info.name!r} ({info.plugin_name}) failed to initialise: {hook_message(e)}",
                source=info.source,
            ) from e
        h = HardwareHandle(info.name, info, comp, State.UNCONFIGURED, states, commands, info.rw_rate)
        for it in states + commands:
            table = self.state_interfaces if isinstance(it, StateInterface) else self.command_interfaces
            if it.name in table:
                raise ConfigError(
                    f"interface {it.name!r} is exported twice (by {self.owner[it.name]!r} and {info.name!r})",
                    source=info.source,
                )
            table[it.name] = it
            self.owner[it.name] = info.name
        self.components[info.name] = h
        return h

    # --- joint limits ------------------------------------------------------------------------------------------
    def import_joint_limiters(self, specs: Iterable[JointLimiterSpec], log: Any) -> None:
        """A limiter for each joint `specs` names (a soft limiter where it has soft limits), logging each as the
        resource manager does; `log` also reports limited commands. Call it after loading the hardware."""
        self._limits_log = log
        for spec in specs:
            where = f"for joint '{spec.joint}' in hardware '{spec.hardware}'"
            if spec.soft_limits is not None:
                log.info(f"Using SoftJointLimiter {where} : '{spec.soft_limits.to_string()}'")
                log.info(f"Creating JointSoftLimiter {where}")
                limiter: JointSaturationLimiter = JointSoftLimiter(spec.joint, spec.limits, spec.soft_limits)
            else:
                log.info(f"Using JointLimiter {where} : '{spec.limits.to_string()}'")
                log.info(f"Creating JointSaturationLimiter {where}")
                limiter = JointSaturationLimiter(spec.joint, spec.limits)
            self.joint_limiters[spec.joint] = JointLimiterEntry(spec.hardware, spec.joint, limiter)
        for entry in self.joint_limiters.values():
            names = [(k, f"{entry.joint}/{k}") for k in INTERFACE_KINDS]
            entry.states = tuple((k, self.state_interfaces[n]) for k, n in names if n in self.state_interfaces)
            entry.commands = tuple(
                (k, self.command_interfaces[n]) for k, n in names
                if n in self.command_interfaces and self.command_interfaces[n].data_type == "double"
            )
        self._limited_claims = None

    def limited_commands(self, names: Iterable[str]) -> tuple[LimitedCommand, ...]:
        """Which of these command interfaces a joint limiter bounds."""
        out = []
        for n in names:
            handle = self.command_interfaces.get(n)
            entry = self.joint_limiters.get(handle.prefix_name) if handle is not None else None
            if entry is not None and any(h is handle for _, h in entry.commands):
                out.append((handle, entry, handle.interface_name))
        return tuple(out)

    def limit_command(self, handle: CommandInterface, entry: JointLimiterEntry, kind: str, period_s: float) -> None:
        """Bound the command a controller wrote on `handle` (raises JointPositionOutOfBounds for a position
        command on a joint measured past its limits: that controller's update fails)."""
        actual = entry.actual()
        desired = JointControlInterfacesData(entry.joint)
        setattr(desired, kind, handle.value)
        command = desired.copy()
        if entry.limiter.enforce(actual, desired, period_s):
            now = time.monotonic()
            if now >= self._limits_logged_s + 1.0:  # throttled before the text is made: it costs more than the limit
                self._limits_logged_s = now
                self._limits_log.error(
                    "Command of at least one joint is out of limits (throttled log). "
                    f"{limiter_data_string(entry.joint, actual, command, desired)} with desired period : "
                    f"{period_s:f} sec."
                )
        value = getattr(desired, kind)
        if value is not None:
            handle.value = value

    def enforce_command_limits(self, period_s: float) -> bool:
        """Bound each limited joint's claimed commands together; True when one was out of its limits."""
        claims = self._limited_claims
        if claims is None:
            claims = self._limited_claims = tuple(
                (e, tuple((k, h) for k, h in e.commands if h.name in self.claimed))
                for e in self.joint_limiters.values()
            )
        enforced = False
        for entry, commands in claims:
            if not commands:
                continue
            desired = JointControlInterfacesData(entry.joint)
            for kind, handle in commands:
                setattr(desired, kind, handle.value)
            if entry.limiter.enforce(entry.actual(), desired, period_s):
                enforced = True
                for kind, handle in commands:
                    value = getattr(desired, kind)
                    if value is not None:
                        handle.value = value
        return enforced

    def reset_joint_limiters(self) -> None:
        for entry in self.joint_limiters.values():
            entry.limiter.reset_internals()

    # --- lifecycle --------------------------------------------------------------------------------------
    def set_state(self, name: str, target: State) -> State:
        """Walk component `name` to `target` through the standard transitions; returns the state reached."""
        h = self.components.get(name)
        if h is None:
            raise TransitionError(f"no hardware component named {name!r}; known: {', '.join(self.components)}")
        comp = h.component
        steps: list[tuple[State, Callable[[], None], str]] = []
        order = [State.UNCONFIGURED, State.INACTIVE, State.ACTIVE]
        if target is State.FINALIZED:
            if h.state is State.ACTIVE:
                steps.append((State.INACTIVE, comp.on_deactivate, "on_deactivate"))
            if h.state in (State.ACTIVE, State.INACTIVE):
                steps.append((State.UNCONFIGURED, comp.on_cleanup, "on_cleanup"))
            if h.state is not State.FINALIZED:
                steps.append((State.FINALIZED, comp.on_shutdown, "on_shutdown"))
        elif target in order:
            if h.state is State.FINALIZED:
                raise TransitionError(f"hardware {name!r} is finalized and can not change state")
            cur, want = order.index(h.state), order.index(target)
            up = {
                1: (State.INACTIVE, comp.on_configure, "on_configure"),
                2: (State.ACTIVE, comp.on_activate, "on_activate"),
            }
            down = {
                1: (State.UNCONFIGURED, comp.on_cleanup, "on_cleanup"),
                2: (State.INACTIVE, comp.on_deactivate, "on_deactivate"),
            }
            steps = [up[i] for i in range(cur + 1, want + 1)] if want > cur else [down[i] for i in range(cur, want, -1)]
        else:
            raise TransitionError(f"hardware can not be set to {target.value!r}")
        for new_state, hook, label in steps:
            try:
                hook()
            except Exception as e:
                self._refresh()
                raise TransitionError(f"hardware {name!r}: {label} failed: {hook_message(e)}") from e
            h.state = new_state
        self._refresh()
        return h.state

    def _refresh(self) -> None:
        comps = list(self.components.values())
        self._active = tuple(h for h in comps if h.state is State.ACTIVE)
        self._readable = tuple(h for h in comps if h.state in (State.ACTIVE, State.INACTIVE))
        # A component with its own (slower) rw_rate needs _rw's bookkeeping; the others are called directly.
        self._slow_active = any(h.rw_rate for h in self._active)
        self._slow_readable = any(h.rw_rate for h in self._readable)
        # The usual robot, one component active at the manager's rate: the cycle calls its read and write itself
        # (None for write when the component's write is marked `writes_nothing`).
        self.single: tuple[HardwareHandle, Callable, Callable | None] | None = None
        if len(self._readable) == 1 and self._active == self._readable and not self._slow_active:
            h = self._active[0]
            c = h.component
            self.single = (h, c.read, None if getattr(c.write, "writes_nothing", False) else c.write)

    # --- availability and claims -------------------------------------------------------------------------
    def state_available(self, name: str) -> bool:
        if name in self.exported_state_owner:
            return name in self._reference_available
        o = self.owner.get(name)
        return (
            name in self.state_interfaces
            and o is not None
            and self.components[o].state in (State.ACTIVE, State.INACTIVE)
        )

    def command_available(self, name: str) -> bool:
        if name in self.reference_owner:
            return name in self._reference_available
        o = self.owner.get(name)
        return name in self.command_interfaces and o is not None and self.components[o].state is State.ACTIVE

    # --- reference interfaces of chainable controllers ---------------------------------------------------
    def import_reference_interfaces(self, controller: str, handles: Iterable[CommandInterface]) -> None:
        self.remove_reference_interfaces(controller)
        for h in handles:
            if h.name in self.command_interfaces:
                raise TransitionError(
                    f"controller '{controller}' exports reference interface '{h.name}', which already exists "
                    f"(owned by '{self.owner.get(h.name) or self.reference_owner.get(h.name)}')"
                )
            self.command_interfaces[h.name] = h
            self.reference_owner[h.name] = controller

    def import_exported_state_interfaces(self, controller: str, handles: Iterable[StateInterface]) -> None:
        for name in [n for n, c in self.exported_state_owner.items() if c == controller]:
            del self.exported_state_owner[name]
            self.state_interfaces.pop(name, None)
        for h in handles:
            if h.name in self.state_interfaces:
                raise TransitionError(
                    f"controller '{controller}' exports state interface '{h.name}', which already exists "
                    f"(owned by '{self.owner.get(h.name) or self.exported_state_owner.get(h.name)}')"
                )
            self.state_interfaces[h.name] = h
            self.exported_state_owner[h.name] = controller

    def remove_reference_interfaces(self, controller: str) -> None:
        """Forget everything `controller` exports (its reference and its state interfaces)."""
        for name in [n for n, c in self.reference_owner.items() if c == controller]:
            del self.reference_owner[name]
            self.command_interfaces.pop(name, None)
            self._reference_available.discard(name)
            self.claimed.pop(name, None)
        for name in [n for n, c in self.exported_state_owner.items() if c == controller]:
            del self.exported_state_owner[name]
            self.state_interfaces.pop(name, None)
            self._reference_available.discard(name)

    def set_reference_available(self, controller: str, available: bool) -> None:
        """The controller's exported interfaces become available (it is active) or not."""
        names = {n for n, c in self.reference_owner.items() if c == controller}
        names |= {n for n, c in self.exported_state_owner.items() if c == controller}
        if available:
            self._reference_available |= names
        else:
            self._reference_available -= names

    def available_command_names(self) -> list[str]:
        return [n for n in self.command_interfaces if self.command_available(n)]

    def available_state_names(self) -> list[str]:
        return [n for n in self.state_interfaces if self.state_available(n)]

    def claim(self, names: Iterable[str], controller: str) -> list[CommandInterface]:
        names = list(names)
        for n in names:
            holder = self.claimed.get(n)
            if holder is not None and holder != controller:
                raise TransitionError(
                    f"Resource conflict for controller '{controller}': command interface '{n}' "
                    f"is already claimed by '{holder}'"
                )
        for n in names:
            self.claimed[n] = controller
        self._limited_claims = None
        return [self.command_interfaces[n] for n in names]

    def release(self, names: Iterable[str]) -> None:
        for n in names:
            self.claimed.pop(n, None)
        self._limited_claims = None

    def components_of(self, interface_names: Iterable[str]) -> set[str]:
        return {self.owner[n] for n in interface_names if n in self.owner}

    # --- mode switches -----------------------------------------------------------------------------------
    def _by_component(self, names: Iterable[str]) -> dict[str, list[str]]:
        out: dict[str, list[str]] = {}
        for n in names:
            if n in self.owner:
                out.setdefault(self.owner[n], []).append(n)
        return out

    def prepare_switch(self, start: list[str], stop: list[str]) -> str | None:
        """None when every component accepts the command-mode switch, else the reason."""
        s, t = self._by_component(start), self._by_component(stop)
        for comp in set(s) | set(t):
            h = self.components[comp]
            try:
                ok = h.component.prepare_command_mode_switch(s.get(comp, []), t.get(comp, []))
            except Exception as e:
                return f"hardware {comp!r} rejected the command mode switch: {hook_message(e)}"
            if not ok:
                return (
                    f"hardware {comp!r} rejected the command mode switch (start {s.get(comp, [])}, "
                    f"stop {t.get(comp, [])})"
                )
        return None

    def perform_switch(self, start: list[str], stop: list[str]) -> str | None:
        s, t = self._by_component(start), self._by_component(stop)
        for comp in set(s) | set(t):
            h = self.components[comp]
            try:
                ok = h.component.perform_command_mode_switch(s.get(comp, []), t.get(comp, []))
            except Exception as e:
                return f"hardware {comp!r} failed the command mode switch: {hook_message(e)}"
            if not ok:
                return f"hardware {comp!r} failed the command mode switch"
        self.reset_joint_limiters()  # the previous commands belong to the modes just left
        return None

    # --- real-time loop ----------------------------------------------------------------------------------
    def _rw(
        self, handles: tuple[HardwareHandle, ...], write: bool, time_ns: int, period_s: float, cm_rate: int
    ) -> list[tuple[str, str]]:
        failed: list[tuple[str, str]] = []
        for h in handles:
            period = period_s
            if h.rw_rate and h.rw_rate < cm_rate:
                # A slower component runs on the cycles that land closest to its own period (decided at read).
                if not write:
                    h.due = h.last_rw_ns is None or (time_ns - h.last_rw_ns) * h.rw_rate >= 0.999e9
                    if h.due:
                        h.rw_period_s = period_s if h.last_rw_ns is None else (time_ns - h.last_rw_ns) * 1e-9
                        h.last_rw_ns = time_ns
                if not h.due:
                    continue
                period = h.rw_period_s
            try:
                ret = (h.component.write if write else h.component.read)(time_ns, period)
                reason = "returned ERROR"
            except Exception as e:
                ret, reason = ReturnType.ERROR, f"raised {hook_message(e)}"
            if ret is not ReturnType.OK:
                if write:
                    h.write_errors += 1
                else:
                    h.read_errors += 1
                failed.append((h.name, f"{'write' if write else 'read'} {reason}"))
        return failed

    def read(self, time_ns: int, period_s: float, cm_rate: int = 0) -> list[tuple[str, str]] | None:
        """Failed components as (name, reason), or None when none failed."""
        if self._slow_readable or len(self._readable) != 1:
            return self._rw(self._readable, False, time_ns, period_s, cm_rate) or None
        # One component at the manager's rate (the usual robot): no per-component bookkeeping.
        h = self._readable[0]
        try:
            ret = h.component.read(time_ns, period_s)
        except Exception as e:
            ret = e
        return None if ret is ReturnType.OK else self.failure(h, False, ret)

    def write(self, time_ns: int, period_s: float, cm_rate: int = 0) -> list[tuple[str, str]] | None:
        """Failed components as (name, reason), or None when none failed."""
        if self._slow_active or len(self._active) != 1:
            return self._rw(self._active, True, time_ns, period_s, cm_rate) or None
        h = self._active[0]
        try:
            ret = h.component.write(time_ns, period_s)
        except Exception as e:
            ret = e
        return None if ret is ReturnType.OK else self.failure(h, True, ret)

    def failure(self, h: HardwareHandle, write: bool, ret: object) -> list[tuple[str, str]]:
        """A component's read or write that returned `ret` (not OK, or the exception it raised), counted and
        worded as read()/write() report it."""
        reason = f"raised {hook_message(ret)}" if isinstance(ret, Exception) else "returned ERROR"
        if write:
            h.write_errors += 1
        else:
            h.read_errors += 1
        return [(h.name, f"{'write' if write else 'read'} {reason}")]

    def fail_component(self, name: str) -> None:
        """After a read/write error: the component goes to unconfigured and its interfaces become unavailable."""
        h = self.components[name]
        try:
            on_error = getattr(h.component, "on_error", None)
            if on_error is not None:
                on_error()
        except Exception as e:
            self._warn(f"hardware {name!r}: on_error raised {hook_message(e)}")
        h.state = State.UNCONFIGURED
        self._refresh()
