"""The controller manager's services (controller_manager_msgs); its parameters are the node's (rcl_interfaces).

Handlers translate requests into ControllerManager calls and back; a failed call answers ok=false and
the manager logs why, as controller_manager does.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from diffctl.control import plugin_registry
from diffctl.control.lifecycle import State, TransitionError
from diffctl.control.manager import ControllerManager
from diffctl.errors import DiffctlError

CM = "controller_manager_msgs/srv/"
ACTIVITY_TYPE = "controller_manager_msgs/msg/ControllerManagerActivity"

class ManagerServices:
    """Registers every service of the manager node on `node` (a bus Node named controller_manager)."""

    def __init__(self, node: Any, cm: ControllerManager) -> None:
        self.node = node
        self.cm = cm
        self.log = node.log
        handlers: dict[str, tuple[str, Callable[[Any], Any]]] = {
            "list_controllers": ("ListControllers", self.list_controllers),
            "list_controller_types": ("ListControllerTypes", self.list_controller_types),
            "list_hardware_components": ("ListHardwareComponents", self.list_hardware_components),
            "list_hardware_interfaces": ("ListHardwareInterfaces", self.list_hardware_interfaces),
            "load_controller": ("LoadController", self._simple(cm.load_controller)),
            "configure_controller": ("ConfigureController", self._simple(cm.configure_controller)),
            "cleanup_controller": ("CleanupController", self._simple(cm.cleanup_controller)),
            "unload_controller": ("UnloadController", self._simple(cm.unload_controller)),
            "switch_controller": ("SwitchController", self.switch_controller),
            "set_hardware_component_state": ("SetHardwareComponentState", self.set_hardware_component_state),
            "reload_controller_libraries": ("ReloadControllerLibraries", self.reload_controller_libraries),
        }
        # Parameters first: a spawner sets `<controller>.type` the moment it sees the services.
        self._declare_parameters()
        self.services = [node.create_service(f"~/{name}", CM + srv, h) for name, (srv, h) in handlers.items()]
        # controller_manager: QoS(1).reliable().transient_local(), published on every change of a controller's
        # or a hardware component's state; a late subscriber gets the last one.
        self.activity = node.create_publisher("~/activity", ACTIVITY_TYPE, latched=True, depth=1, reliable=True)
        cm.on_activity = self.publish_activity
        self.publish_activity()  # the hardware brought up before the publisher existed

    def close(self) -> None:
        self.cm.on_activity = None
        for s in self.services:
            s.close()

    def publish_activity(self) -> None:
        """controller_manager_msgs/ControllerManagerActivity: every controller's and component's lifecycle state."""
        t_ns = self.node.clock.now_ns()
        with self.cm._lock:
            controllers = [{"name": n, "state": {"id": mc.state.id, "label": mc.state.value}}
                           for n, mc in self.cm.controllers.items()]
            components = [{"name": n, "state": {"id": h.state.id, "label": h.state.value}}
                          for n, h in self.cm.rm.components.items()]
        self.activity.publish({
            "header": {"stamp": {"sec": t_ns // 1_000_000_000, "nanosec": t_ns % 1_000_000_000}, "frame_id": ""},
            "controllers": controllers,
            "hardware_components": components,
        })

    # --- controller_manager_msgs ------------------------------------------------------------------------
    def _simple(self, fn: Callable[[str], Any]) -> Callable[[Any], dict[str, Any]]:
        def handler(req: Any) -> dict[str, Any]:
            try:
                fn(req.name)
                return {"ok": True}
            except DiffctlError as e:
                self.log.error(str(e))
                return {"ok": False}

        return handler

    def list_controllers(self, _req: Any) -> dict[str, Any]:
        out = []
        with self.cm._lock:
            for mc in self.cm.controllers.values():
                out.append(
                    {
                        "name": mc.name,
                        "state": mc.state.value,
                        "type": mc.type_name,
                        "is_async": False,
                        "update_rate": mc.update_rate,
                        "claimed_interfaces": list(mc.claimed),
                        "required_command_interfaces": list(mc.required_command),
                        "required_state_interfaces": list(mc.required_state),
                        "is_chainable": bool(getattr(mc.instance, "is_chainable", False)),
                        "is_chained": bool(getattr(mc.instance, "is_in_chained_mode", lambda: False)()),
                        "reference_interfaces": [r.name for r in getattr(mc.instance, "reference_interfaces", [])],
                        "chain_connections": self._chain_connections(mc),
                    }
                )
        return {"controller": out}

    def _chain_connections(self, mc: Any) -> list[dict[str, Any]]:
        """The controllers whose reference interfaces `mc` claims, with those interfaces."""
        owners: dict[str, list[str]] = {}
        for name in mc.claimed:
            owner = self.cm.rm.reference_owner.get(name)
            if owner is not None:
                owners.setdefault(owner, []).append(name)
        return [{"name": o, "reference_interfaces": names} for o, names in owners.items()]

    def list_controller_types(self, _req: Any) -> dict[str, Any]:
        names = plugin_registry.controller_types()
        return {"types": names, "base_classes": [plugin_registry.base_class_of(n) for n in names]}

    def _interfaces(self, names: list[str], command: bool) -> list[dict[str, Any]]:
        rm = self.cm.rm
        out = []
        table = rm.command_interfaces if command else rm.state_interfaces
        for n in names:
            avail = rm.command_available(n) if command else rm.state_available(n)
            handle = table.get(n)
            out.append(
                {
                    "name": n,
                    # the handle's type, as the hardware declared it (ros2_control's default: double)
                    "data_type": handle.data_type if handle is not None else "double",
                    "is_available": avail,
                    "is_claimed": command and n in rm.claimed,
                }
            )
        return out

    def list_hardware_components(self, _req: Any) -> dict[str, Any]:
        out = []
        with self.cm._lock:
            for h in self.cm.rm.components.values():
                out.append(
                    {
                        "name": h.name,
                        "type": h.info.type,
                        "is_async": False,
                        "rw_rate": h.rw_rate or self.cm.update_rate,
                        "class_type": h.plugin_name,  # Jazzy fills the deprecated field with the plugin name too
                        "plugin_name": h.plugin_name,
                        "state": {"id": h.state.id, "label": h.state.value},
                        "command_interfaces": self._interfaces([c.name for c in h.commands], True),
                        "state_interfaces": self._interfaces([s.name for s in h.states], False),
                    }
                )
        return {"component": out}

    def list_hardware_interfaces(self, _req: Any) -> dict[str, Any]:
        rm = self.cm.rm
        with self.cm._lock:
            return {
                "command_interfaces": self._interfaces(sorted(rm.command_interfaces), True),
                "state_interfaces": self._interfaces(sorted(rm.state_interfaces), False),
            }

    def switch_controller(self, req: Any) -> dict[str, Any]:
        timeout_s = int(req.timeout.sec) + int(req.timeout.nanosec) * 1e-9
        ok, msg = self.cm.switch_controller(
            list(req.activate_controllers),
            list(req.deactivate_controllers),
            int(req.strictness),
            bool(req.activate_asap),
            timeout_s,
        )
        return {"ok": ok, "message": msg}

    def set_hardware_component_state(self, req: Any) -> dict[str, Any]:
        target = req.target_state
        try:
            state = State.parse(target.label) if target.label else State.from_id(int(target.id))
        except (TransitionError, ValueError):
            self.log.error(f"set_hardware_component_state: unknown target state id={target.id} label={target.label!r}")
            h = self.cm.rm.components.get(req.name)
            cur = h.state if h else State.UNKNOWN
            return {"ok": False, "state": {"id": cur.id, "label": cur.value}}
        try:
            reached = self.cm.set_hardware_component_state(req.name, state)
            return {"ok": reached is state, "state": {"id": reached.id, "label": reached.value}}
        except DiffctlError as e:
            self.log.error(str(e))
            h = self.cm.rm.components.get(req.name)
            cur = h.state if h else State.UNKNOWN
            return {"ok": False, "state": {"id": cur.id, "label": cur.value}}

    def reload_controller_libraries(self, req: Any) -> dict[str, Any]:
        # Python plugins cannot be unloaded from a running process; refuse while controllers are loaded.
        if self.cm.controllers and not req.force_kill:
            self.log.error("can not reload controller libraries while controllers are loaded (use force_kill)")
            return {"ok": False}
        for name in list(self.cm.controllers):
            mc = self.cm.controllers[name]
            if mc.state is State.ACTIVE:
                self.cm.switch_controller([], [name], 2)
            self.cm.unload_controller(name)
        plugin_registry.rescan()
        return {"ok": True}

    # --- the manager's own parameters (served by the node's parameter services, as every node's) --------
    def _declare_parameters(self) -> None:
        from diffctl.bus.parameters import ParameterDescriptor

        self.node.declare_parameter(
            "update_rate",
            self.cm.update_rate,
            ParameterDescriptor(description="controller manager update rate in Hz", read_only=True),
        )
        self.node.add_on_set_parameters_callback(self._on_set_parameters)

    def _on_set_parameters(self, changes: dict[str, Any]) -> str | None:
        """`<controller>.type`, `.params_file`, … set at runtime (the spawner does) reach the manager."""
        settings = ("type", "params_file", "update_rate", "fallback_controllers", "node_options_args")
        for name, value in changes.items():
            prefix, _, key = name.rpartition(".")
            if prefix and key in settings:
                try:
                    self.cm.set_controller_param(prefix, key, value)
                except DiffctlError as e:
                    return str(e)
        return None
