"""joy_linux's joy_linux_node on the client Node (node name joy_node): its parameters, `joy`,
`joy/set_feedback` (JoyFeedbackArray, rumble through `dev_ff`), /diagnostics, and the thread that opens `dev`
(retrying every second, reopening a device that went away) and publishes its state.
"""

from __future__ import annotations

import os
import threading
import time
from typing import Any

from diffctl.diagnostic_updater.updater import ERROR, OK, Status, Updater
from diffctl.joy.linux_joystick import DeviceLost, Joystick, device_name, is_character_device, joystick_paths
from diffctl.joy_linux.force_feedback import Rumble, gain_event
from diffctl.joy_linux.joy_state import LinuxJoyState, corrected

NODE_NAME = "joy_node"


def find_by_name(name: str, log: Any) -> str:
    """The first /dev/input/js* character device called `name` (every one seen is logged), else ""."""
    for path in joystick_paths():
        if not is_character_device(path):
            continue
        found = device_name(path)
        if found is None and not os.access(path, os.R_OK):
            continue
        found = found or "Unknown"
        log.info(f"Found joystick: {found} ({path}).")
        if found == name:
            return path
    return ""


class LinuxJoy:
    def __init__(self, node: Any) -> None:
        from diffctl.interfaces import get_interface

        self.node, self.log, self.clock = node, node.get_logger(), node.get_clock()
        self.diagnostics = Updater(node)
        self.diagnostics.add("Joystick Driver Status", self.report)
        self.diagnostics.set_hardware_id("none")
        self.joy = get_interface("sensor_msgs/msg/Joy")
        self.pub = node.create_publisher(self.joy, "joy", 10)
        node.create_subscription(get_interface("sensor_msgs/msg/JoyFeedbackArray"), "joy/set_feedback",
                                 self.on_feedback, 10)
        self.dev = str(node.declare_parameter("dev", "/dev/input/js0").value)
        self.dev_name = str(node.declare_parameter("dev_name", "").value)
        self.dev_ff = str(node.declare_parameter("dev_ff", "/dev/input/event0").value)
        self.params, warnings = corrected(
            float(node.declare_parameter("deadzone", 0.05).value),
            float(node.declare_parameter("autorepeat_rate", 20.0).value),
            float(node.declare_parameter("coalesce_interval", 0.001).value),
            bool(node.declare_parameter("default_trig_val", False).value),
            bool(node.declare_parameter("sticky_buttons", False).value))
        if self.dev_name:
            path = find_by_name(self.dev_name, self.log)
            if path:
                self.log.info(f"Using {path} as joystick device.")
                self.dev = path
            else:
                self.log.error(f"Couldn't find a joystick with name {self.dev_name}. Falling back to default device.")
        for text in warnings:
            self.log.warning(text)
        self.is_open = False
        self.events = self.publications = 0
        self.last_report_s = self.clock.now_ns() / 1e9
        self.rumble: Rumble | None = None
        self.stop = threading.Event()
        node.context.on_shutdown(self.stop.set)
        threading.Thread(target=self.loop, name="joy-linux-device", daemon=True).start()

    def report(self, stat: Status) -> None:
        now = self.clock.now_ns() / 1e9
        interval = now - self.last_report_s
        if self.is_open:
            stat.summary(OK, "OK")
        else:
            stat.summary(ERROR, "Joystick not open.")
        stat.add("topic", self.pub.topic_name)
        stat.add("device", self.dev)
        stat.add("device name", self.dev_name)
        stat.add("dead zone", self.params.deadzone)
        stat.add("autorepeat rate (Hz)", self.params.autorepeat_rate_hz)
        stat.add("coalesce interval (s)", self.params.coalesce_interval_s)
        stat.add("recent joystick event rate (Hz)", _rate(self.events, interval))
        stat.add("recent publication rate (Hz)", _rate(self.publications, interval))
        stat.add("subscribers", self.pub.get_subscription_count())
        stat.add("default trig val", self.params.default_trig_val)
        stat.add("sticky buttons", self.params.sticky_buttons)
        self.events = self.publications = 0
        self.last_report_s = now

    def on_feedback(self, msg: Any) -> None:
        rumble = self.rumble
        if rumble is not None:
            rumble.set_feedback([(int(f.type), int(f.id), float(f.intensity)) for f in msg.array])

    def open_device(self) -> Joystick | None:
        """Open `dev`, waiting a second between tries (the first failure logged); None once stopping."""
        first_fault = True
        while not self.stop.is_set():
            try:
                # The kernel's initial-state records can be those of the last close: open, close, open again.
                Joystick(self.dev).close()
                return Joystick(self.dev)
            except OSError:
                if first_fault:
                    self.log.error(f"Couldn't open joystick {self.dev}. Will retry every second.")
                    first_fault = False
            self.stop.wait(1.0)
        return None

    def open_rumble(self) -> None:
        self.rumble = None
        if not self.dev_ff:
            return
        try:
            fd = os.open(self.dev_ff, os.O_RDWR | os.O_NONBLOCK)
        except OSError as e:
            self.log.warning(f"Couldn't open joystick force feedback: {e.strerror}")
            return
        rumble = Rumble(fd)
        try:
            os.write(fd, gain_event(100))
        except OSError as e:
            self.log.warning(f"Couldn't open joystick force feedback: {e.strerror}")
        rumble.upload()
        self.rumble = rumble

    def close_rumble(self) -> None:
        rumble, self.rumble = self.rumble, None
        if rumble is not None:
            try:
                os.close(rumble.fd)
            except OSError:
                pass

    def publish(self, state: LinuxJoyState) -> None:
        msg = self.joy(axes=list(state.axes), buttons=list(state.buttons))
        msg.header.frame_id = "joy"
        msg.header.stamp = self.clock.now().to_msg()
        self.pub.publish(msg)
        self.publications += 1

    def serve(self, device: Joystick) -> None:
        """Publish from an open device until it goes away or the node stops."""
        state = LinuxJoyState(self.params, time.monotonic_ns())
        while not self.stop.is_set():
            try:
                records = device.read(min(state.wait_s(time.monotonic_ns()), 0.25))
                if self.rumble is not None:
                    self.rumble.play()
            except (DeviceLost, OSError):
                return
            now = time.monotonic_ns()
            if not records and now < state.deadline_ns:
                continue  # woke early to look at the stop flag
            for record in records or [None]:
                if record is not None:
                    self.events += 1
                if state.step(record, now):
                    self.publish(state)
            for record in state.unknown:
                self.log.warning(f"joy_linux_node: Unknown event type. Please file a ticket. time={record.time_ms}, "
                                 f"value={record.value}, type={record.type:X}h, number={record.number}")
            state.unknown.clear()

    def loop(self) -> None:
        try:
            while not self.stop.is_set():
                self.is_open = False
                self.diagnostics.force_update()
                device = self.open_device()
                if device is None:
                    break
                self.open_rumble()
                self.log.info(f"Opened joystick: {self.dev}. deadzone_: {self.params.deadzone:f}.")
                self.is_open = True
                self.diagnostics.force_update()
                try:
                    self.serve(device)
                finally:
                    device.close()
                    self.close_rumble()
                if not self.stop.is_set():
                    self.log.error("Connection to joystick device lost unexpectedly. Will reopen.")
        except Exception as e:  # the node is being torn down under the thread
            if not self.stop.is_set():
                self.log.error(f"joystick thread ended: {e}")


def _rate(count: int, interval_s: float) -> float:
    if interval_s == 0:
        return float("nan") if count == 0 else float("inf")
    return count / interval_s


def run() -> int:
    from diffctl.client import component
    from diffctl.client.node import Node

    def make() -> Any:
        node = Node(NODE_NAME, client_library="rclcpp")
        LinuxJoy(node)
        return node

    return component.run(make)
