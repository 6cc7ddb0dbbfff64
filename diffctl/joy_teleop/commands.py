"""joy_teleop's commands, read from the node's parameters as teleop_tools' joy_teleop reads them (Jazzy).

Each top-level parameter group is a command: `type` topic (`interface_type` a message, `topic_name`,
`deadman_buttons` / `deadman_axes` / `deadman_axes_negative`, then either a fixed `message_value` sent once per
press or `axis_mappings` of `<field-path>: {axis|button: i, scale, offset}` or `{value: v}` (with `index` into an
array field) published on every Joy message while the deadman holds), `service` (`service_name`,
`service_request`) or `action` (`action_name`, `action_goal`), the latter two triggered by `buttons` / `axes` /
`axes_negative` and called once per press. Groups that are not commands (use_sim_time …) are skipped.
"""

from __future__ import annotations

from typing import Any

from diffctl.errors import ConfigError


class JoyTeleopException(ConfigError):
    """A command the configuration cannot make (upstream's JoyTeleopException)."""


def interface_class(type_name: str, kind: str) -> Any:
    """`pkg/msg/Type` → its class; the middle part must be `kind` (msg, srv, action)."""
    from diffctl.interfaces import get_interface

    parts = type_name.split("/")
    if len(parts) != 3:
        raise JoyTeleopException(f"Invalid type_name '{type_name}'")
    if parts[1] != kind:
        raise JoyTeleopException(f"Cannot use interface of type '{parts[1]}' for an '{kind}'")
    return get_interface(type_name)


def _owner(msg: Any, path: str) -> tuple[Any, str]:
    """`twist-linear-x` → (msg.twist.linear, "x"): fields joined by dashes, as upstream names them."""
    names = path.strip("-").split("-")
    target = msg
    for name in names[:-1]:
        target = getattr(target, name)
    return target, names[-1]


class Trigger:
    """The buttons and axes that make a command active: every listed button at 1, axis at 1.0 (or -1.0)."""

    def __init__(self, name: str, config: dict[str, Any], buttons: str, axes: str, negative: str) -> None:
        self.buttons = list(config.get(buttons, []))
        self.axes = list(config.get(axes, []))
        self.negative = list(config.get(negative, []))
        if not (self.buttons or self.axes or self.negative):
            raise JoyTeleopException(f"No buttons, axes or negative_axes configured for command '{name}'")
        self.active = False

    def update(self, joy: Any) -> None:
        buttons, axes = list(joy.buttons), list(joy.axes)
        lowest_button = min(self.buttons) if self.buttons else 0
        lowest_axis = min(self.axes) if self.axes else 0
        lowest_negative = min(self.negative) if self.negative else 0
        self.active = True
        if len(buttons) <= lowest_button and len(axes) <= lowest_axis and len(axes) <= lowest_negative:
            return  # a message too short for this command: upstream leaves it active
        # indices past the message's end are skipped, as upstream skips them
        self.active &= all(buttons[i] == 1 for i in self.buttons if i < len(buttons))
        self.active &= all(axes[i] == 1.0 for i in self.axes if i < len(axes))
        self.active &= all(axes[i] == -1.0 for i in self.negative if i < len(axes))


class TopicCommand:
    def __init__(self, name: str, config: dict[str, Any], node: Any) -> None:
        from diffctl.client.qos import QoSDurabilityPolicy, QoSHistoryPolicy, QoSProfile, QoSReliabilityPolicy

        self.trigger = Trigger(name, config, "deadman_buttons", "deadman_axes", "deadman_axes_negative")
        self.node = node
        self.type = interface_class(str(config.get("interface_type", "")), "msg")
        self.fixed = None
        if "message_value" in config:
            self.fixed = self.type()
            for path, spec in config["message_value"].items():
                owner, field = _owner(self.fixed, path)
                setattr(owner, field, spec["value"])
        self.mappings: dict[str, dict[str, Any]] = dict(config.get("axis_mappings", {}))
        for spec in self.mappings.values():
            if not any(k in spec for k in ("axis", "button", "value")):
                raise JoyTeleopException(f"Axis mapping for '{name}' must have an axis, button, or value")
            if "axis" in spec and "offset" not in spec:
                raise JoyTeleopException(f"Axis mapping for '{name}' must have an offset")
            if "axis" in spec and "scale" not in spec:
                raise JoyTeleopException(f"Axis mapping for '{name}' must have a scale")
        if self.fixed is None and not self.mappings:
            raise JoyTeleopException(f"No 'message_value' or 'axis_mappings' configured for command '{name}'")
        if self.fixed is not None and self.mappings:
            raise JoyTeleopException(
                f"Only one of 'message_value' or 'axis_mappings' can be configured for command '{name}'")
        qos = QoSProfile(history=QoSHistoryPolicy.KEEP_LAST, depth=1, reliability=QoSReliabilityPolicy.RELIABLE,
                         durability=QoSDurabilityPolicy.VOLATILE)
        self.pub = node.create_publisher(self.type, config["topic_name"], qos)

    def _value(self, joy: Any, spec: dict[str, Any]) -> Any:
        log = self.node.get_logger()
        for key, values, what in (("axis", joy.axes, "axes"), ("button", joy.buttons, "buttons")):
            if key in spec:
                index = spec[key]
                if len(values) > index:
                    return values[index] * spec.get("scale", 1.0) + spec.get("offset", 0.0)
                log.error(f"Joystick has only {len(values)} {what} (indexed from 0),but #{index} was referenced "
                          "in config.")
                return 0.0
        return spec["value"]

    def run(self, joy: Any) -> None:
        was = self.trigger.active
        self.trigger.update(joy)
        if not self.trigger.active or (self.fixed is not None and was):
            return  # a fixed message goes once per press; mappings stream while the deadman holds
        msg = self.fixed if self.fixed is not None else self.type()
        if self.fixed is None:
            for path, spec in self.mappings.items():
                value = self._value(joy, spec)
                owner, field = _owner(msg, path)
                current = getattr(owner, field)
                if isinstance(current, (str, bytes)) or not hasattr(current, "__len__"):
                    setattr(owner, field, value)
                    continue
                items = list(current)  # an array field: the value goes at `index`, zeros before it
                index = spec.get("index", 0)
                items += [0] * (index + 1 - len(items))
                items[index] = type(items[0])(value) if items and index > 0 else value
                setattr(owner, field, items)
        if hasattr(msg, "header"):
            msg.header.stamp = self.node.get_clock().now().to_msg()
        self.pub.publish(msg)


class CallCommand:
    """A service call or action goal, sent once per press once the server is there."""

    def __init__(self, name: str, config: dict[str, Any], node: Any, kind: str) -> None:
        from diffctl.interfaces.runtime.set_message import set_message_fields

        self.trigger = Trigger(name, config, "buttons", "axes", "axes_negative")
        cls = interface_class(str(config.get("interface_type", "")), "srv" if kind == "service" else "action")
        if kind == "service":
            self.request = cls.Request()
            set_message_fields(self.request, config.get("service_request", {}))
            self.client = node.create_client(cls, config["service_name"])
            self.ready = self.client.service_is_ready
            self.send = lambda: self.client.call_async(self.request)
        else:
            from diffctl.client.action import ActionClient

            self.request = cls.Goal()
            set_message_fields(self.request, config.get("action_goal", {}))
            self.client = ActionClient(node, cls, config["action_name"])
            self.ready = self.client.server_is_ready
            self.send = lambda: self.client.send_goal_async(self.request)
        self.was_ready = False

    def run(self, joy: Any) -> None:
        was_active = self.trigger.active
        self.trigger.update(joy)
        if not self.trigger.active:
            return
        was_ready, self.was_ready = self.was_ready, bool(self.ready())
        if self.was_ready and not (was_ready and was_active):
            self.send()  # a new press, or the server just appeared while held


def nested(flat: dict[str, Any]) -> dict[str, Any]:
    """`drive.axis_mappings.twist-linear-x.axis: 1` → {'drive': {'axis_mappings': {…}}}."""
    out: dict[str, Any] = {}
    for name in sorted(flat):
        target = out
        *parents, leaf = name.split(".")
        for part in parents:
            target = target.setdefault(part, {})
            if not isinstance(target, dict):
                break
        else:
            target[leaf] = flat[name]
    return out


def build(node: Any, parameters: dict[str, Any]) -> list[Any]:
    commands: list[Any] = []
    for name, config in nested(parameters).items():
        if not isinstance(config, dict):
            continue  # use_sim_time and other plain parameters
        kind = config.get("type")
        if kind == "topic":
            commands.append(TopicCommand(name, config, node))
        elif kind in ("service", "action"):
            commands.append(CallCommand(name, config, node, kind))
        else:
            raise JoyTeleopException(f"unknown type '{kind}' for command '{name}'")
    return commands
