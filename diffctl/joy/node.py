"""joy's joy_node on the client Node: its parameters, `joy` and `joy/set_feedback`, and the thread that reads
the joystick and publishes.

Devices are numbered as SDL numbers them for the real node, from what this machine offers: the paths in
SDL_JOYSTICK_DEVICE (colon-separated, SDL's own variable) that exist first, then /dev/input/js0, js1, … . `device_name`
picks the first whose name is exactly that; else `device_id` is the index. A device that is absent is looked
for again every second, as SDL notices a joystick plugged in later; one that goes away empties the message
and stops publishing until it is back.
"""

from __future__ import annotations

import os
import threading
import time
from collections import deque
from typing import Any

from diffctl.errors import ParameterError
from diffctl.joy.joy_state import JoyParams, JoyState, Layout, Slot, sdl_layout
from diffctl.joy.linux_joystick import (
    JS_EVENT_AXIS,
    JS_EVENT_BUTTON,
    DeviceLost,
    Joystick,
    JsEvent,
    device_name,
    joystick_paths,
)

NODE_NAME = "joy_node"
DEVICE_LIST_ENV = "SDL_JOYSTICK_DEVICE"
RESCAN_S = 1.0


def candidates() -> list[str]:
    """The joysticks present, numbered as device_id counts them (a listed path that does not exist is none)."""
    extra = [p for p in os.environ.get(DEVICE_LIST_ENV, "").split(":") if p and os.path.exists(p)]
    return list(dict.fromkeys(extra + joystick_paths()))


def declare(node: Any) -> tuple[int, str, JoyParams]:
    """joy_node's parameters, in its order and with its defaults; out-of-range values refused, quoted."""
    device_id = node.declare_parameter("device_id", 0).value
    name = node.declare_parameter("device_name", "").value
    deadzone = node.declare_parameter("deadzone", 0.05).value
    if not 0.0 <= deadzone <= 1.0:
        raise ParameterError(f"Deadzone must be between 0.0 and 1.0 (got {deadzone!r})", field="deadzone")
    rate = node.declare_parameter("autorepeat_rate", 20.0).value
    if not 0.0 <= rate <= 1000.0:
        raise ParameterError(f"Autorepeat rate must be >= 0.0 and <= 1000.0 (got {rate!r})", field="autorepeat_rate")
    sticky = node.declare_parameter("sticky_buttons", False).value
    coalesce = node.declare_parameter("coalesce_interval_ms", 1).value
    if coalesce < 0:
        raise ParameterError(f"coalesce_interval_ms must be positive (got {coalesce!r})", field="coalesce_interval_ms")
    return int(device_id), str(name), JoyParams(float(deadzone), float(rate), bool(sticky), int(coalesce))


class JoyReader:
    """The device side of joy_node: finds and opens the joystick, turns its events into Joy messages."""

    def __init__(self, node: Any, device_id: int, name: str, params: JoyParams) -> None:
        from diffctl.interfaces import get_interface

        self.node, self.device_id, self.name, self.params = node, device_id, name, params
        self.log = node.get_logger()
        self.clock = node.get_clock()
        self.joy = get_interface("sensor_msgs/msg/Joy")
        self.pub = node.create_publisher(self.joy, "joy", 10)
        node.create_subscription(get_interface("sensor_msgs/msg/JoyFeedback"), "joy/set_feedback",
                                 self.on_feedback, 10)
        self.state = JoyState(params, self.clock.now_ns())
        self.device: Joystick | None = None
        self.layout: Layout | None = None
        self.pending: deque[JsEvent] = deque()
        self._unmatched: list[str] | None = None
        self.stop = threading.Event()
        node.context.on_shutdown(self.stop.set)
        self.thread = threading.Thread(target=self.loop, name="joy-device", daemon=True)
        self.thread.start()

    def on_feedback(self, msg: Any) -> None:
        # Rumble plays through SDL's haptic device, which the joystick API has not got: as the real node does
        # with a joystick without rumble, the request is dropped.
        return None

    def choose(self) -> str | None:
        paths = candidates()
        if self.name:
            for path in paths:
                if (device_name(path) or "Unknown") == self.name:
                    return path
            if paths != self._unmatched:
                self._unmatched = paths
                self.log.warning(f"Could not get joystick with name {self.name}: none among "
                                 f"{', '.join(paths) or 'the joysticks present (none)'}")
            return None
        return paths[self.device_id] if 0 <= self.device_id < len(paths) else None

    def open(self) -> None:
        path = self.choose()
        if path is None:
            return
        try:
            device = Joystick(path)
        except OSError as e:
            self.log.warning(f"Unable to open joystick {self.device_id}: {path}: {e.strerror}")
            return
        ident = device.identity
        self.layout = sdl_layout(ident.axis_codes) if ident.axis_codes is not None else None
        self.state.attach(self.layout.axes if self.layout else None, ident.buttons)
        self.device = device
        self.log.info("No haptic (rumble) available, skipping initialization")
        self.log.info(f"Opened joystick: {ident.name or path}.  deadzone: {self.params.deadzone:f}")

    def close(self, why: str) -> None:
        if self.device is not None:
            self.log.info(f"joystick {self.device.path} closed: {why}")
            self.device.close()
        self.device, self.layout = None, None
        self.pending.clear()
        self.state.detach()

    def apply(self, event: JsEvent, now_ns: int) -> bool:
        """One event into the message; whether it asks to publish."""
        state, n = self.state, event.number
        if event.kind == JS_EVENT_BUTTON:
            if event.is_init and not event.value:
                state.initial_button(n)
                return False
            return state.button(n, bool(event.value))
        if event.kind == JS_EVENT_AXIS:
            slot = self.layout.slot(n) if self.layout is not None else Slot(n)
            if slot is None:
                self.log.warning("Saw axes too large for this device, ignoring")
                return False
            if slot.hat is not None:
                return not (event.is_init and event.value == 0) and state.hat(slot, event.value)
            if event.is_init:
                state.initial_axis(slot.index, event.value)
                return False
            return state.axis(slot.index, event.value, now_ns)
        self.log.info(f"Unknown event type {event.type}")
        return False

    def publish(self, now_ns: int) -> None:
        msg = self.joy(axes=list(self.state.axes), buttons=list(self.state.buttons))
        msg.header.frame_id = "joy"
        msg.header.stamp = self.clock.now().to_msg()
        self.pub.publish(msg)

    def step(self) -> None:
        assert self.device is not None
        if not self.pending:
            try:
                self.pending.extend(self.device.read(self.state.wait_ms() / 1000.0))
            except DeviceLost as e:
                self.close(str(e))
                return
        now = self.clock.now_ns()
        asked = self.apply(self.pending.popleft(), now) if self.pending else False
        for text in self.state.warnings:
            self.log.warning(text)
        self.state.warnings.clear()
        if self.state.settle(asked, now):
            self.publish(now)

    def loop(self) -> None:
        next_scan = 0.0
        try:
            while not self.stop.is_set():
                if self.device is None:
                    if time.monotonic() >= next_scan:
                        next_scan = time.monotonic() + RESCAN_S
                        self.open()
                    if self.device is None:
                        self.stop.wait(max(0.0, next_scan - time.monotonic()))
                        continue
                self.step()
        except Exception as e:  # the node is being torn down under the thread
            if not self.stop.is_set():
                self.log.error(f"joystick thread ended: {e}")
        finally:
            if self.device is not None:
                self.device.close()


def run() -> int:
    from diffctl.client import component
    from diffctl.client.node import Node

    def make() -> Any:
        node = Node(NODE_NAME, client_library="rclcpp")
        JoyReader(node, *declare(node))
        return node

    return component.run(make)
