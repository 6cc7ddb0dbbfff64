"""diagnostic_updater's Updater (Jazzy) on a client Node.

It declares `diagnostic_updater.period` (1.0 s) and `diagnostic_updater.use_fqn` (false), publishes a
DiagnosticArray on /diagnostics (depth 1) every period of the node's clock, one status per task named
"<node name>: <task name>", and "Node starting up" as each task is added. Values are written as C++'s
stream output writes them (six significant digits, bools as True/False).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from diffctl.interfaces import get_interface as msg

OK, WARN, ERROR, STALE = 0, 1, 2, 3


def cpp_text(value: object) -> str:
    """`std::stringstream << value` for the types diagnostics carry."""
    if isinstance(value, bool):
        return "True" if value else "False"
    if isinstance(value, float):
        if math.isnan(value):
            return "nan" if math.copysign(1.0, value) > 0 else "-nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return format(value, ".6g")
    return str(value)


class Status:
    """DiagnosticStatusWrapper: a status being filled by a task."""

    def __init__(self, name: str, hardware_id: str) -> None:
        self.name, self.hardware_id = name, hardware_id
        self.level, self.message = ERROR, "No message was set"
        self.values: list[tuple[str, str]] = []

    def summary(self, level: int, message: str) -> None:
        self.level, self.message = level, message

    def add(self, key: str, value: object) -> None:
        self.values.append((key, cpp_text(value)))


class Updater:
    def __init__(self, node: Any, period_s: float = 1.0) -> None:
        self.node = node
        self.clock = node.get_clock()
        self.pub = node.create_publisher(msg("diagnostic_msgs/msg/DiagnosticArray"), "/diagnostics", 1)
        period = node.get_parameter("diagnostic_updater.period").value \
            if node.has_parameter("diagnostic_updater.period") \
            else node.declare_parameter("diagnostic_updater.period", float(period_s)).value
        use_fqn = node.get_parameter("diagnostic_updater.use_fqn").value \
            if node.has_parameter("diagnostic_updater.use_fqn") \
            else node.declare_parameter("diagnostic_updater.use_fqn", False).value
        self.node_name = node.get_fully_qualified_name() if use_fqn else node.get_name()
        self.hardware_id = ""
        self._warned_no_hardware_id = False
        self.tasks: list[tuple[str, Callable[[Status], None]]] = []
        self.timer = node.create_timer(float(period), self.force_update)

    def set_hardware_id(self, hardware_id: str) -> None:
        self.hardware_id = hardware_id

    def add(self, name: str, task: Callable[[Status], None]) -> None:
        self.tasks.append((name, task))
        starting = Status(name, "")
        starting.summary(OK, "Node starting up")
        self._publish([starting])

    def force_update(self) -> None:
        statuses = []
        for name, task in self.tasks:
            status = Status(name, self.hardware_id)
            task(status)
            statuses.append(status)
        if not self.hardware_id and not self._warned_no_hardware_id and all(s.level == OK for s in statuses):
            self._warned_no_hardware_id = True
            self.node.get_logger().warning(
                "diagnostic_updater: No HW_ID was set. This is probably a bug. Please report it. For devices that "
                "do not have a HW_ID, set this value to 'none'. This warning only occurs once all diagnostics are "
                "OK. It is okay to wait until the device is open before calling setHardwareID.")
        self._publish(statuses)

    def _publish(self, statuses: list[Status]) -> None:
        kv, status_cls = msg("diagnostic_msgs/msg/KeyValue"), msg("diagnostic_msgs/msg/DiagnosticStatus")
        array = msg("diagnostic_msgs/msg/DiagnosticArray")(status=[
            status_cls(level=bytes([s.level]), name=f"{self.node_name}: {s.name}", message=s.message,
                       hardware_id=s.hardware_id, values=[kv(key=k, value=v) for k, v in s.values])
            for s in statuses])
        array.header.stamp = self.clock.now().to_msg()
        self.pub.publish(array)
