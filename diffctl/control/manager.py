"""The controller manager core: loaded controllers, hardware, switching and the read → update → write cycle.

Node-free: the node that exposes it (ros2_control_node.py, or the simulator's gz_ros2_control plugin) gives
it a logger, a factory for controller nodes (client Nodes, see controller_node.py) and the executor they are
spun by, and drives `read/update/write` from its real-time loop. Administrative calls (load, configure,
switch, …) come from service threads; they are serialised among themselves, and a switch is carried out
by the real-time loop at the end of `update()` (as controller_manager does), the caller waiting for it.
When no loop runs (unit tests, before start-up) a switch is carried out at once.
"""

from __future__ import annotations

import dataclasses
import functools
import threading
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from diffctl.client.clock_type import ClockType
from diffctl.client.duration import Duration
from diffctl.client.ros_time import Time
from diffctl.control.controller_interface import (
    CallbackReturn,
    CommandInterface,
    ControllerInterfaceParams,
    InterfaceConfiguration,
    ReturnType,
    StateInterface,
)
from diffctl.control.controller_node import controller_node_arguments
from diffctl.control.hardware_interface import HardwareComponent, HardwareInfo
from diffctl.control.joint_limits.joint_limits_urdf import JointLimiterSpec, hardware_joint_limits
from diffctl.control.lifecycle import ManagedController, State, TransitionError, hook_message
from diffctl.control.params import ControllerSpec, ManagerParams, with_controller_param
from diffctl.control.plugin_registry import controller_class
from diffctl.control.realtime_publisher import hold as hold_publishing
from diffctl.control.realtime_publisher import release as release_publishing
from diffctl.control.resource_manager import ResourceManager
from diffctl.control.switching import STRICT, ControllerView, SwitchPlan, chain_order, plan_switch
from diffctl.errors import ConfigError

# (controller name, its node's arguments) → the controller's client Node
NodeFactory = Callable[[str, list[str]], Any]
_OK = ReturnType.OK
_ROS_TIME = ClockType.ROS_TIME


@dataclass
class _PendingSwitch:
    plan: SwitchPlan
    done: threading.Event = field(default_factory=threading.Event)
    ok: bool = False
    message: str = ""


class ControllerManager:
    def __init__(
        self,
        params: ManagerParams,
        *,
        log: Any,
        node_factory: NodeFactory,
        robot_description: str = "",
        cancel: threading.Event | None = None,
        executor: Any = None,
    ) -> None:
        self.params = params
        self.log = log  # an rclpy-API logger (debug/info/warn/error)
        self.node_factory = node_factory
        self.executor = executor  # spins the controllers' nodes (their subscriptions, parameter services)
        self.robot_description = robot_description
        self.cancel = cancel
        self.rm = ResourceManager(log.warn)
        self.controllers: dict[str, ManagedController] = {}
        self.loop_running = False
        self._lock = threading.RLock()  # held by the real-time cycle and by structural changes
        self._admin = threading.RLock()  # serialises service calls
        self._active: tuple[ManagedController, ...] = ()
        # The cycle's view of `_active`: (controller, its update, whether that update takes integer nanoseconds,
        # runs every cycle, the claimed commands a joint limiter bounds or None). diffctl's own controllers take
        # (time_ns, period_ns) through `update_ns`, the same work as update(time, period) without building the
        # Time and Duration; any other controller (a user's subclass of them too) gets update(time, period).
        self._updates: tuple[tuple[ManagedController, Callable[[Any, Any], Any], bool, bool, Any], ...] = ()
        self._period = _duration(0)  # the last cycle's period, handed on while it does not change
        self._pending: _PendingSwitch | None = None
        self.cycle_count = 0
        # Called whenever the controllers or the hardware components change state (the node's ~/activity
        # publisher, as controller_manager's publish_activity).
        self.on_activity: Callable[[], None] | None = None
        self.on_node_released: Callable[[Any], None] | None = None  # a controller's node is about to go

    def _activity(self) -> None:
        if self.on_activity is not None:
            try:
                self.on_activity()
            except Exception as e:  # a failed publish must not fail the transition that caused it
                self.log.warn(f"could not publish the activity: {hook_message(e)}")

    @property
    def update_rate(self) -> int:
        return self.params.update_rate

    # ---------------------------------------------------------------------------------------------- hardware
    def load_hardware(
        self, infos: Sequence[HardwareInfo], factory: Callable[[HardwareInfo], HardwareComponent] | None = None
    ) -> None:
        """Load every component (made by `factory` when given, else from the plugin registry), then bring it to
        its initial state (active unless the parameters say not)."""
        with self._admin, self._lock:
            limiters = self._joint_limiters(infos)
            for info in infos:
                component = factory(info) if factory is not None else None
                self.rm.load(info, self.log, self.update_rate, self.cancel, component)
            if limiters:
                self.rm.import_joint_limiters(limiters, self.log)
            for info in infos:
                if info.name in self.params.hardware_unconfigured:
                    continue
                target = State.INACTIVE if info.name in self.params.hardware_inactive else State.ACTIVE
                try:
                    self.rm.set_state(info.name, target)
                except TransitionError as e:
                    raise ConfigError(str(e), source=info.source) from e
                self.log.info(f"hardware '{info.name}' ({info.plugin_name}) is {target.value}")

    def _joint_limiters(self, infos: Sequence[HardwareInfo]) -> list[JointLimiterSpec]:
        """The joints' limiters when the parameters enforce command limits (a bad description raises before any
        hardware is loaded), as controller_manager's init_resource_manager decides."""
        if not self.params.enforce_command_limits:
            self.log.info("Enforcing command limits is disabled. Command limits from URDF will be ignored.")
            return []
        self.log.info("Enforcing command limits is enabled...")
        source = next((i.source for i in infos if i.source), None) or "robot_description"
        specs, notes = hardware_joint_limits(infos, self.robot_description, source)
        if not self.robot_description.strip():
            self.log.info("no robot description: the joints' limits are their <ros2_control> interfaces' min/max")
        for level, text in notes:
            (self.log.warn if level == "warn" else self.log.info)(text)
        return specs

    def set_hardware_component_state(self, name: str, target: State) -> State:
        with self._admin, self._lock:
            h = self.rm.components.get(name)
            if h is None:
                raise TransitionError(f"no hardware component named '{name}'; known: {', '.join(self.rm.components)}")
            # Controllers that would lose interfaces are deactivated first.
            losing = set(h.commands) if target is not State.ACTIVE else set()
            if target in (State.UNCONFIGURED, State.FINALIZED):
                losing |= set(h.states)
            names = {i.name for i in losing}
            users = [mc for mc in self._active if names & set(mc.claimed + mc.required_state)]
            for mc in users:
                self.log.warn(f"deactivating controller '{mc.name}': hardware '{name}' goes to {target.value}")
                self._deactivate(mc)
            self._refresh_active()
            try:
                return self.rm.set_state(name, target)
            finally:
                self._activity()

    # ---------------------------------------------------------------------------------------------- loading
    def set_controller_param(self, name: str, key: str, value: Any) -> None:
        with self._admin:
            self.params = with_controller_param(self.params, name, key, value)

    def set_controller_spec(self, spec: ControllerSpec) -> None:
        """What the manager node's parameters say of one controller (`<name>.type`, `.params_file`, …)."""
        with self._admin:
            self.params = dataclasses.replace(self.params, controllers={**self.params.controllers, spec.name: spec})

    def load_controller(self, name: str, type_name: str | None = None) -> ManagedController:
        with self._admin:
            if name in self.controllers:
                raise TransitionError(f"a controller named '{name}' was already loaded inside the controller manager")
            spec = self.params.controllers.get(name)
            ctype = type_name or (spec.type if spec else None)
            if not ctype:
                raise TransitionError(
                    f"the 'type' param was not defined for '{name}' (set '{name}.type' in the "
                    "controller manager's parameters or pass the controller's --param-file)"
                )
            try:
                cls = controller_class(ctype)
            except ConfigError as e:
                raise TransitionError(f"could not load controller '{name}': {e}") from e
            files = spec.params_files if spec else ()
            for f in files:
                if not Path(f).is_file():
                    raise TransitionError(f"could not load controller '{name}': parameter file {f!r} not found "
                                          f"(from {name}.params_file)")
            arguments = controller_node_arguments(
                self.params.node_arguments, files, self.params.use_sim_time, spec.node_options_args if spec else ()
            )
            try:
                node = self.node_factory(name, arguments)
            except Exception as e:
                raise TransitionError(f"could not load controller '{name}': {hook_message(e)}") from e
            inst = cls()
            try:
                ret = inst.init(ControllerInterfaceParams(name, self.robot_description, self.update_rate, node))
                if ret is not CallbackReturn.SUCCESS:
                    raise TransitionError(f"on_init returned {ret.name}")
            except Exception as e:
                _close(node)
                raise TransitionError(f"could not initialize controller '{name}': {hook_message(e)}") from e
            fallbacks = spec.fallback_controllers if spec else ()
            mc = ManagedController(name, ctype, inst, State.UNCONFIGURED, self.update_rate,
                                   fallback_controllers=fallbacks)
            if self.executor is not None:
                self.executor.add_node(node)
            with self._lock:
                self.controllers[name] = mc
            self.log.info(f"loaded controller '{name}' ({ctype})")
            self._activity()
            return mc

    def _get(self, name: str) -> ManagedController:
        mc = self.controllers.get(name)
        if mc is None:
            known = ", ".join(self.controllers) or "none"
            raise TransitionError(f"controller '{name}' is not loaded (loaded: {known})")
        return mc

    def configure_controller(self, name: str) -> None:
        with self._admin:
            mc = self._get(name)
            if mc.state is State.UNCONFIGURED:
                mc.update_rate = _controller_rate(mc, self.update_rate, self.log)
            try:
                mc.configure()
            finally:
                self._activity()
            inst = mc.instance
            if inst.is_chainable():  # what it exports becomes claimable command / readable state interfaces
                try:
                    references = inst.export_reference_interfaces()
                    states = inst.export_state_interfaces()
                    with self._lock:
                        self.rm.import_reference_interfaces(name, references)
                        self.rm.import_exported_state_interfaces(name, states)
                except Exception as e:
                    with self._lock:
                        self.rm.remove_reference_interfaces(name)
                    mc.cleanup()
                    raise TransitionError(f"controller '{name}': exporting its interfaces failed: {hook_message(e)}"
                                          ) from e
            mc.required_command = self._resolve(mc.instance.command_interface_configuration(), command=True)
            mc.required_state = self._resolve(mc.instance.state_interface_configuration(), command=False)
            self.log.info(f"configured controller '{name}'")

    def cleanup_controller(self, name: str) -> None:
        with self._admin:
            self._get(name).cleanup()
            with self._lock:
                self.rm.remove_reference_interfaces(name)
            self.log.info(f"cleaned up controller '{name}'")

    def unload_controller(self, name: str) -> None:
        with self._admin:
            mc = self._get(name)
            if mc.state is State.ACTIVE:
                raise TransitionError(f"could not unload controller '{name}': it is still active; deactivate it first")
            try:
                mc.shutdown()
            finally:
                with self._lock:
                    del self.controllers[name]
                    self.rm.remove_reference_interfaces(name)
                self._release_node(mc)
                self._activity()
            self.log.info(f"unloaded controller '{name}'")

    def _resolve(self, cfg: InterfaceConfiguration, *, command: bool) -> list[str]:
        if cfg.type == "none":
            return []
        if cfg.type == "all":
            if command:  # every hardware command interface; other controllers' references are claimed by name
                return [n for n in self.rm.command_interfaces if n not in self.rm.reference_owner]
            return list(self.rm.state_interfaces)
        if cfg.type == "individual":
            return list(cfg.names)
        raise TransitionError(f"interface configuration type {cfg.type!r} is not one of all, individual, none")

    # ---------------------------------------------------------------------------------------------- switching
    def switch_controller(
        self,
        activate: Sequence[str],
        deactivate: Sequence[str],
        strictness: int = 0,
        activate_asap: bool = False,
        timeout_s: float = 0.0,
    ) -> tuple[bool, str]:
        """Check and carry out a switch; (ok, message). Waits for the real-time loop up to `timeout_s` (0 = 1 s)."""
        with self._admin:
            with self._lock:
                plan = self._plan(activate, deactivate, strictness or self.params.default_strictness)
            for w in plan.warnings:
                self.log.warn(w)
            if not plan.ok or plan.empty:
                if not plan.ok:
                    self.log.error(plan.message)
                return plan.ok, plan.message
            start = [i for n in plan.activate for i in self.controllers[n].required_command]
            stop = [i for n in plan.deactivate for i in self.controllers[n].claimed]
            reason = self.rm.prepare_switch(start, stop)
            if reason:
                self.log.error(reason)
                return False, reason
            pending = _PendingSwitch(plan)
            if not self.loop_running:
                with self._lock:
                    self._execute(pending)
                self._activity()
                return pending.ok, pending.message
            with self._lock:
                self._pending = pending
            if activate_asap:
                self.log.debug("Requested atomic controller switch from realtime loop")
            else:
                self.log.info("Requested controller switch from non-realtime loop")
            timeout = timeout_s if timeout_s > 0 else 1.0
            if not pending.done.wait(timeout):
                with self._lock:
                    if self._pending is pending:
                        self._pending = None
                        msg = f"Switch controller timed out after {timeout:g} seconds!"
                        self.log.error(msg)
                        return False, msg
            self._activity()
            return pending.ok, pending.message

    def _plan(self, activate: Sequence[str], deactivate: Sequence[str], strictness: int) -> SwitchPlan:
        views = {}
        for n, mc in self.controllers.items():
            if mc.state is State.INACTIVE:
                # Resolved again at switch time: hardware may have come up since configure.
                mc.required_command = self._resolve(mc.instance.command_interface_configuration(), command=True)
                mc.required_state = self._resolve(mc.instance.state_interface_configuration(), command=False)
            views[n] = ControllerView(mc.state, mc.required_command, mc.required_state)
        return plan_switch(
            views,
            list(activate),
            list(deactivate),
            strictness,
            claimed=self.rm.claimed,
            command_available=self.rm.command_available,
            state_available=self.rm.state_available,
            reference_owner=self.rm.reference_owner,
            state_owner=self.rm.exported_state_owner,
        )

    def _execute(self, pending: _PendingSwitch) -> None:
        """Carry out a checked switch (real-time thread, `_lock` held): mode switch → deactivate → chained modes
        → activate, as controller_manager's manage_switch."""
        plan = pending.plan
        start = [i for n in plan.activate for i in self.controllers[n].required_command]
        stop = [i for n in plan.deactivate for i in self.controllers[n].claimed]
        failures = []
        reason = self.rm.perform_switch(start, stop)
        if reason:
            failures.append(reason)
        for n in plan.deactivate:
            self._deactivate(self.controllers[n])
        if not reason:
            # A controller about to be activated takes the chained mode it will have once the switch is done.
            claims_after = {i: c for i, c in self.rm.claimed.items()}
            for n in plan.activate:
                claims_after.update(dict.fromkeys(self.controllers[n].required_command, n))
            for n in plan.activate:
                inst = self.controllers[n].instance
                chained = any(claims_after.get(r.name) for r in getattr(inst, "reference_interfaces", ()))
                if inst.is_chainable() and inst.is_in_chained_mode() != chained:
                    inst.set_chained_mode(chained)
            for n in plan.activate:
                err = self._activate(self.controllers[n])
                if err:
                    failures.append(err)
        failures += self._sync_chained_modes()
        self._refresh_active()
        pending.ok = not failures
        pending.message = "; ".join(failures)
        for f in failures:
            self.log.error(f)
        done = [f"activated {n}" for n in plan.activate if self.controllers[n].state is State.ACTIVE]
        done += [f"deactivated {n}" for n in plan.deactivate]
        if done:
            self.log.info("switch: " + ", ".join(done))
        pending.done.set()

    def _sync_chained_modes(self) -> list[str]:
        """Put every chainable controller in chained mode exactly while an active controller claims its
        references; an active one is restarted for it (deactivate → mode → activate), as controller_manager
        does. The failures, if any."""
        failures = []
        for mc in self.controllers.values():
            inst = mc.instance
            if not inst.is_chainable():
                continue
            chained = any(self.rm.claimed.get(r.name) for r in inst.reference_interfaces)
            if inst.is_in_chained_mode() == chained:
                continue
            active = mc.state is State.ACTIVE
            if active:
                self._deactivate(mc)
            inst.set_chained_mode(chained)
            if active:
                err = self._activate(mc)
                if err:
                    failures.append(err)
        return failures

    def _activate(self, mc: ManagedController) -> str | None:
        inst = mc.instance
        try:
            cmds: list[CommandInterface] = self.rm.claim(mc.required_command, mc.name)
        except TransitionError as e:
            return f"could not activate controller '{mc.name}': {e}"
        mc.claimed = list(mc.required_command)
        inst.command_interfaces = cmds
        inst.state_interfaces = [self.rm.state_interfaces[n] for n in mc.required_state]
        try:
            mc.call("on_activate", inst.on_activate)
        except TransitionError as e:
            self.rm.release(mc.claimed)
            mc.claimed = []
            inst.release_interfaces()
            return f"could not activate {str(e).removeprefix('controller ')}"
        mc.state = State.ACTIVE
        self.rm.set_reference_available(mc.name, True)
        mc.last_update_ns = None
        mc.last_error = ""
        return None

    def _deactivate(self, mc: ManagedController) -> None:
        try:
            mc.call("on_deactivate", mc.instance.on_deactivate)
        except TransitionError as e:
            self.log.error(str(e))
        self.rm.release(mc.claimed)
        mc.claimed = []
        mc.instance.release_interfaces()
        self.rm.set_reference_available(mc.name, False)
        mc.state = State.INACTIVE

    def _refresh_active(self) -> None:
        # Controllers chained in front of others update first, so a following one reads this cycle's references;
        # exporters of state interfaces before their readers.
        active = [n for n, mc in self.controllers.items() if mc.state is State.ACTIVE]
        views = {n: ControllerView(mc.state, mc.claimed, mc.required_state) for n, mc in self.controllers.items()}
        order = chain_order(active, views, self.rm.reference_owner, state_owner=self.rm.exported_state_owner)
        self._active = tuple(self.controllers[n] for n in order)
        rate = self.params.update_rate
        limited = self.rm.limited_commands if self.rm.joint_limiters else None
        self._updates = tuple(
            (mc, *_update_entry(mc.instance), mc.update_rate >= rate,
             (limited(mc.claimed) or None) if limited else None)
            for mc in self._active
        )

    # ---------------------------------------------------------------------------------------------- real time
    def read(self, time_ns: int, period_s: float) -> None:
        with self._lock:
            failed = self.rm.read(time_ns, period_s, self.params.update_rate)
            if failed:
                self._hardware_failed(failed)

    def write(self, time_ns: int, period_s: float) -> None:
        with self._lock:
            failed = self.rm.write(time_ns, period_s, self.params.update_rate)
            if failed:
                self._hardware_failed(failed)

    def cycle(self, time_ns: int, period_s: float) -> None:
        """read → update → write, as the real-time loop runs them, under one acquisition of the lock; what the
        controllers published goes to the publishing thread once the commands are written."""
        held = hold_publishing()
        try:
            with self._lock:
                rate = self.params.update_rate
                rm = self.rm
                single = rm.single
                if single is None:
                    failed = rm.read(time_ns, period_s, rate)
                    if failed:
                        self._hardware_failed(failed)
                    self._update(time_ns, period_s, rate)
                    failed = rm.write(time_ns, period_s, rate)
                    if failed:
                        self._hardware_failed(failed)
                    return
                # One component at the manager's rate (the usual robot): its read and write called here, each
                # call a frame fewer on every cycle; a failure is counted and worded by the resource manager.
                h, read, write = single
                try:
                    ret = read(time_ns, period_s)
                except Exception as e:
                    ret = e
                if ret is not _OK:
                    self._hardware_failed(rm.failure(h, False, ret))
                self._update(time_ns, period_s, rate)
                if write is not None and rm.single is single:
                    try:
                        ret = write(time_ns, period_s)
                    except Exception as e:
                        ret = e
                    if ret is not _OK:
                        self._hardware_failed(rm.failure(h, True, ret))
        finally:
            release_publishing(held)

    def _hardware_failed(self, failed: list[tuple[str, str]]) -> None:
        for comp, reason in failed:
            h = self.rm.components[comp]
            names = {i.name for i in h.commands} | {i.name for i in h.states}
            users = [mc for mc in self._active if names & set(mc.claimed + mc.required_state)]
            self.log.error(
                f"hardware '{comp}' {reason}: deactivating controllers "
                f"[{', '.join(mc.name for mc in users)}]; the component goes to unconfigured"
            )
            for mc in users:
                mc.last_error = f"hardware '{comp}' {reason}"
                self._deactivate(mc)
            self.rm.fail_component(comp)
        self._sync_chained_modes()
        self._refresh_active()
        self._activity()

    def update(self, time_ns: int, period_s: float) -> None:
        with self._lock:
            held = hold_publishing()
            try:
                self._update(time_ns, period_s, self.params.update_rate)
            finally:
                release_publishing(held)

    def _update(self, time_ns: int, period_s: float, rate: int) -> None:
        """The controllers' updates (`_lock` held, publishing held: what they publish reaches the publishing
        thread once they all ran; woken in the middle of them, it would take the GIL from this loop)."""
        self.cycle_count += 1
        failed: list[tuple[ManagedController, str]] | None = None
        cycle_period_ns = round(period_s * 1e9)
        time = None  # the public API's Time, built for the first controller that takes it
        for mc, update, takes_ns, every_cycle, limited in self._updates:
            period_ns = cycle_period_ns
            if not every_cycle and mc.last_update_ns is not None:
                # ros2_control: run on the cycle whose elapsed time is closest to the controller's period.
                actual = (time_ns - mc.last_update_ns) * 1e-9
                r = mc.update_rate
                if abs(actual * r - 1.0) > abs((actual + 1.0 / rate) * r - 1.0):
                    continue
                period_ns = time_ns - mc.last_update_ns
            try:
                if takes_ns:
                    ret = update(time_ns, period_ns)
                else:
                    if time is None:
                        time = _ros_time(time_ns)
                    period = self._period
                    if period.nanoseconds != period_ns:
                        period = _duration(period_ns)
                        if period_ns == cycle_period_ns:
                            self._period = period
                    ret = update(time, period)
                if limited is not None:
                    # ros2_control limits a command as the controller sets it, at the manager's period
                    rm_limit, desired_s = self.rm.limit_command, 1.0 / rate
                    for handle, entry, kind in limited:
                        rm_limit(handle, entry, kind, desired_s)
            except Exception as e:
                if not self.params.handle_exceptions:
                    raise
                ret = e
            mc.last_update_ns = time_ns
            mc.update_count += 1
            if ret is not _OK:
                reason = f"update() raised {hook_message(ret)}" if isinstance(ret, Exception) else (
                    "update() returned ERROR")
                failed = [*(failed or ()), (mc, reason)]
        if failed:
            self._controllers_failed(failed)
        if self.rm.joint_limiters:
            try:
                self.rm.enforce_command_limits(period_s)
            except Exception as e:  # a joint past its limits under a position command: its controller failed above
                self.log.error(f"enforcing the command limits failed: {hook_message(e)}", throttle_duration_sec=1.0)
        if self._pending is not None:
            pending, self._pending = self._pending, None
            self._execute(pending)

    def _controllers_failed(self, failed: list[tuple[ManagedController, str]]) -> None:
        fallbacks: list[str] = []
        for mc, reason in failed:
            mc.last_error = reason
            self.log.error(f"controller '{mc.name}' {reason}: deactivating it")
            try:
                mc.call("on_error", mc.instance.on_error)
            except TransitionError as e:
                self.log.error(str(e))
            self._deactivate(mc)
            fallbacks.extend(mc.fallback_controllers)
        self._sync_chained_modes()
        self._refresh_active()
        if fallbacks:
            plan = self._plan(fallbacks, [], STRICT)
            if plan.ok and not plan.empty:
                self.log.warn(f"activating fallback controllers [{', '.join(plan.activate)}]")
                self._execute(_PendingSwitch(plan))
            elif not plan.ok:
                self.log.error(f"fallback controllers could not be activated: {plan.message}")
        self._activity()  # the failed controllers' and the fallbacks' new states

    # ---------------------------------------------------------------------------------------------- shutdown
    def shutdown(self) -> None:
        """Deactivate, unload every controller and finalize the hardware (manager exit)."""
        with self._admin, self._lock:
            if self._pending is not None:
                self._pending.message = "controller manager is shutting down"
                self._pending.done.set()
                self._pending = None
            for mc in reversed(list(self.controllers.values())):
                if mc.state is State.ACTIVE:
                    self._deactivate(mc)
                try:
                    mc.shutdown()
                except Exception as e:
                    self.log.warn(f"controller '{mc.name}': shutdown: {hook_message(e)}")
                self._release_node(mc)
            self.controllers.clear()
            self._active = ()
            self._updates = ()
            for name in list(self.rm.components):
                try:
                    self.rm.set_state(name, State.FINALIZED)
                except Exception as e:
                    self.log.warn(f"hardware '{name}': shutdown: {hook_message(e)}")

    def _release_node(self, mc: ManagedController) -> None:
        node = mc.instance._node
        if node is None:
            return
        if self.executor is not None:
            self.executor.remove_node(node)
        if self.on_node_released is not None:
            self.on_node_released(node)
        _close(node)

    # ---------------------------------------------------------------------------------------------- views
    def interface_users(self) -> dict[str, str]:
        return dict(self.rm.claimed)

    def state_value(self, name: str) -> float:
        it: StateInterface | CommandInterface | None = self.rm.state_interfaces.get(name)
        it = it or self.rm.command_interfaces.get(name)
        return float("nan") if it is None else it.value


def _controller_rate(mc: ManagedController, cm_rate: int, log: Any) -> int:
    """The rate a controller runs at, from its node's `update_rate`, as controller_interface's configure decides
    it (raises TransitionError on a negative rate)."""
    raw = mc.instance.get_node().get_parameter("update_rate").value
    if raw < 0:
        raise TransitionError(f"controller '{mc.name}': Update rate cannot be a negative value!")
    if raw == 0 or raw == cm_rate:
        return cm_rate
    if raw > cm_rate:
        log.warn(
            f"controller '{mc.name}': The update rate of the controller : '{raw} Hz' cannot be higher than the "
            f"update rate of the controller manager : '{cm_rate} Hz'. Setting it to the update rate of the "
            "controller manager."
        )
        return cm_rate
    if cm_rate % raw:
        achievable = cm_rate // round(cm_rate / raw)
        log.warn(
            f"controller '{mc.name}': The requested update rate of '{raw}' Hz is not achievable with the controller "
            f"manager update rate of '{cm_rate}' Hz. Setting it to the closest achievable frequency "
            f"'{achievable}' Hz."
        )
        return achievable
    return raw


def _update_entry(instance: Any) -> tuple[Callable[[Any, Any], Any], bool]:
    """(the update the cycle calls, whether it takes integer nanoseconds): `update_ns` when the controller's own
    class defines it (diffctl's controllers; a subclass, which may override update(), is called through update())."""
    if "update_ns" in vars(type(instance)):
        return instance.update_ns, True
    return instance.update, False


# Made once per cycle, on the real-time thread: the fast paths (the values are the manager's own clock's).
_ros_time = functools.partial(Time.from_nanoseconds, clock_type=_ROS_TIME)
_duration = Duration.from_nanoseconds


def _close(node: Any) -> None:
    try:
        node.destroy_node()
    except Exception:  # a controller node that fails to close must not block unloading
        pass
