"""What gz-sim's joint controllers (JointController, JointPositionController) read alike: the joints named by
`joint_name`, a PID from `p_gain` … `cmd_offset`, and their command, one number per message, from gz.msgs.Double
on the command topic or, with `use_actuator_msg`, entry `actuator_number` of a gz.msgs.Actuators field."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from diffctl.description.model import Plugin
from diffctl.sim.entity import Entity
from diffctl.sim.plugins.attachments import Attachments
from diffctl.sim.plugins.base import PluginContext, bool_param, float_param
from diffctl.sim.plugins.gz_pid import GzPid
from diffctl.sim.plugins.system_support import find_joints, int_param, valid_topic

PID_TAGS = ("p_gain", "i_gain", "d_gain", "i_max", "i_min", "cmd_max", "cmd_min", "cmd_offset")
# gz-sim's JointController's; its JointPositionController's differ in the integral and derivative gains
CONTROLLER_PID = {"p_gain": 1.0, "i_gain": 0.0, "d_gain": 0.0, "i_max": 1.0, "i_min": -1.0,
                  "cmd_max": 1000.0, "cmd_min": -1000.0, "cmd_offset": 0.0}  # fmt: skip


def pid_from(plugin: Plugin, source: str, defaults: dict[str, float], prefix: str = "") -> GzPid:
    def num(tag: str) -> float:
        value = float_param(plugin, prefix + tag, defaults[tag], source=source)
        return defaults[tag] if value is None else value

    return GzPid(*(num(tag) for tag in PID_TAGS))  # (GzPid's fields are in this order)


def command_topic(plugin: Plugin, model: str, default: str, use_actuator_msg: bool) -> str:
    """gz-sim's precedence for a joint controller's command topic: topic, sub_topic, /actuators, default."""
    if plugin.get("topic"):
        return valid_topic(plugin.get("topic") or "")
    if plugin.get("sub_topic"):
        return valid_topic(f"/model/{model}/{plugin.get('sub_topic')}")
    return "/actuators" if use_actuator_msg else valid_topic(default)


def double_value(fields: dict[str, Any]) -> float:
    return float(fields.get("data", 0.0) or 0.0)


class CommandedJoints:
    """The joints a controller drives (found at once, each missing one warned about) and, once `listen` is
    called, the subscription its commands arrive on; `close` lets go of it and of the step hook added."""

    def __init__(self, ctx: PluginContext, entity: Entity, plugin: Plugin, system: str) -> None:
        self._ctx, self._entity, self._plugin, self._system = ctx, entity, plugin, system
        self.names = [n for n in plugin.get_all("joint_name") if n.strip()]
        self.joints = find_joints(ctx, entity, self.names, system)
        self.attached = Attachments(ctx)

    def listen(self, default_tail: str, field: str, on_value: Callable[[float], None]) -> str | None:
        """Subscribe to the commands (default topic /model/<model>/joint/<first joint>/<default_tail>) and
        return the topic; with no joint named, warn as gz-sim does and return None."""
        plugin, source, model = self._plugin, self._entity.model.source, self._entity.name
        asked = bool_param(plugin, "use_actuator_msg", False, source=source)
        use_actuator = asked and bool(plugin.get("actuator_number"))
        number = int_param(plugin, "actuator_number", 0, source=source)
        if not self.names:
            self._ctx.log.warn(f"{self._system} on model {model!r}: failed to get any <joint_name>")
            return None
        default = f"/model/{model}/joint/{self.names[0]}/{default_tail}"
        topic = command_topic(plugin, model, default, use_actuator)
        if not use_actuator:
            self.attached.subscribe(topic, "gz.msgs.Double", lambda fields: on_value(double_value(fields)))
            return topic

        def on_actuators(fields: dict[str, Any]) -> None:
            values = fields.get(field)
            if values is not None and number < len(values):
                on_value(float(values[number]))

        self.attached.subscribe(topic, "gz.msgs.Actuators", on_actuators)
        return topic

    def close(self) -> None:
        self.attached.close()
