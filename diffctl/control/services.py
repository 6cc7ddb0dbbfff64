"""The controller manager's services (controller_manager_msgs) and ~/activity, on its client Node.

Handlers translate requests into ControllerManager calls and back; a failed call answers ok=false and
the manager logs why, as controller_manager does. load_controller reads the controller's settings from the
manager node's parameters at that moment (`<name>.type`, `.params_file`, declaring `.fallback_controllers`
and `.node_options_args` as controller_manager does), and a switch with strictness 0 uses
`defaults.switch_controller.strictness`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from diffctl.client.callback_groups import ReentrantCallbackGroup
from diffctl.client.interfaces import cls
from diffctl.client.parameter import Parameter
from diffctl.client.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from diffctl.control import plugin_registry
from diffctl.control.lifecycle import State, TransitionError
from diffctl.control.manager import ControllerManager
from diffctl.control.params import STRICTNESS, controller_spec
from diffctl.errors import DiffctlError
from diffctl.interfaces.runtime.set_message import set_message_fields

CM = "controller_manager_msgs/srv/"
ACTIVITY_TYPE = "controller_manager_msgs/msg/ControllerManagerActivity"
# controller_manager's ~/activity: QoS(1).reliable().transient_local()
ACTIVITY_QOS = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.TRANSIENT_LOCAL)


class ManagerServices:
    """Registers every service of the manager node on `node` (the manager's client Node)."""

    def __init__(self, node: Any, cm: ControllerManager) -> None:
        self.node = node
        self.cm = cm
        self.log = node.get_logger()
        handlers: dict[str, tuple[str, Callable[[Any], Any]]] = {
            "list_controllers": ("ListControllers", self.list_controllers),
            "list_controller_types": ("ListControllerTypes", self.list_controller_types),
            "list_hardware_components": ("ListHardwareComponents", self.list_hardware_components),
            "list_hardware_interfaces": ("ListHardwareInterfaces", self.list_hardware_interfaces),
            "load_controller": ("LoadController", self._simple(self.load_controller)),
            "configure_controller": ("ConfigureController", self._simple(cm.configure_controller)),
            "cleanup_controller": ("CleanupController", self._simple(cm.cleanup_controller)),
            "unload_controller": ("UnloadController", self._simple(cm.unload_controller)),
            "switch_controller": ("SwitchController", self.switch_controller),
            "set_hardware_component_state": ("SetHardwareComponentState", self.set_hardware_component_state),
            "reload_controller_libraries": ("ReloadControllerLibraries", self.reload_controller_libraries),
        }
        # One reentrant group: the listings answer while a switch waits for the control loop (controller_manager
        # serialises its services, so `list_controllers` would hang behind a switch in a paused simulation); the
        # manager serialises the changes itself.
        group = ReentrantCallbackGroup()
        self.services = [node.create_service(cls(CM + srv), f"~/{name}", _answering(h), callback_group=group)
                         for name, (srv, h) in handlers.items()]
        # Published on every change of a controller's or a hardware component's state; a late subscriber gets
        # the last one.
        self.activity = node.create_publisher(cls(ACTIVITY_TYPE), "~/activity", ACTIVITY_QOS)
        cm.on_activity = self.publish_activity
        self.publish_activity()  # the hardware brought up before the publisher existed

    def close(self) -> None:
        self.cm.on_activity = None
        for s in self.services:
            s.destroy()
        self.activity.destroy()

    def publish_activity(self) -> None:
        """controller_manager_msgs/ControllerManagerActivity: every controller's and component's lifecycle state."""
        t_ns = self.node.get_clock().now().nanoseconds
        with self.cm._lock:
            controllers = [{"name": n, "state": {"id": mc.state.id, "label": mc.state.value}}
                           for n, mc in self.cm.controllers.items()]
            components = [{"name": n, "state": {"id": h.state.id, "label": h.state.value}}
                          for n, h in self.cm.rm.components.items()]
        msg = cls(ACTIVITY_TYPE)()
        set_message_fields(msg, {
            "header": {"stamp": {"sec": t_ns // 1_000_000_000, "nanosec": t_ns % 1_000_000_000}, "frame_id": ""},
            "controllers": controllers,
            "hardware_components": components,
        })
        self.activity.publish(msg)

    # --- controller_manager_msgs ------------------------------------------------------------------------
    def load_controller(self, name: str) -> None:
        """controller_manager's load_controller(name): its settings are the node's parameters now."""
        node = self.node
        if not node.has_parameter(f"{name}.type"):
            node.declare_parameter(f"{name}.type", Parameter.Type.STRING)
        for key in ("fallback_controllers", "node_options_args"):
            if not node.has_parameter(f"{name}.{key}"):
                node.declare_parameter(f"{name}.{key}", Parameter.Type.STRING_ARRAY)
                node.set_parameters([Parameter(f"{name}.{key}", Parameter.Type.STRING_ARRAY, [])])
        settings = {}
        for key in ("type", "params_file", "fallback_controllers", "node_options_args"):
            p = node.get_parameter_or(f"{name}.{key}")
            if p.type_ != Parameter.Type.NOT_SET:
                settings[key] = list(p.value) if isinstance(p.value, list | tuple) else p.value
        self.cm.set_controller_spec(controller_spec(name, settings, f"{node.get_fully_qualified_name()} parameters"))
        self.cm.load_controller(name)

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
        strictness = int(req.strictness)
        if strictness == 0:  # the node's default, as it is now
            default = self.node.get_parameter_or("defaults.switch_controller.strictness").value
            strictness = STRICTNESS.get(default, STRICTNESS["best_effort"])
        ok, msg = self.cm.switch_controller(
            list(req.activate_controllers),
            list(req.deactivate_controllers),
            strictness,
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
        try:
            for name in list(self.cm.controllers):
                mc = self.cm.controllers.get(name)
                if mc is not None and mc.state is State.ACTIVE:
                    self.cm.switch_controller([], [name], 2)
                self.cm.unload_controller(name)
        except DiffctlError as e:  # another call changed the controllers meanwhile
            self.log.error(f"reload_controller_libraries: {e}")
            return {"ok": False}
        plugin_registry.rescan()
        return {"ok": True}



def _answering(handler: Callable[[Any], dict[str, Any]]) -> Callable[[Any, Any], Any]:
    """An rclpy service callback filling the response from a handler's dict of its fields."""
    def callback(request: Any, response: Any) -> Any:
        set_message_fields(response, handler(request))
        return response

    return callback
