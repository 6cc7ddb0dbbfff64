"""The linear battery of Gazebo's LinearBatteryPlugin as pure math: charge, smoothed current, voltage, state of
charge, stepped once per physics step (gz-sim src/systems/battery_plugin/LinearBatteryPlugin.cc,
`OnUpdateVoltage`).

Open-circuit voltage E = e0 + e1 (1 - q / c) - r i, with q the charge (Ah), c the capacity (Ah), i the current
low-pass filtered with time constant tau. Without `fix_issue_225` the state of charge is estimated as gz-sim
does it (gazebosim/gz-sim issue 225): every step subtracts the charge of the last 100 steps' currents, so it
falls about a hundred times too fast; with it, soc = q / c.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass


@dataclass(frozen=True)
class BatteryParams:
    name: str
    voltage_v: float  # the initial voltage, reported until the first update
    capacity_ah: float
    initial_charge_ah: float
    e0_v: float = 0.0
    e1_v: float = 0.0
    resistance_ohm: float = 0.0
    tau_s: float = 1.0
    charging_time_h: float = 0.0
    fix_issue_225: bool = False


class LinearBattery:
    HISTORY = 100

    def __init__(self, p: BatteryParams) -> None:
        self.p = p
        self.reset()

    def reset(self) -> None:
        self.voltage_v = self.p.voltage_v
        self.q_ah = self.p.initial_charge_ah
        self.soc = self.q_ah / self.p.capacity_ah
        self.i_raw_a = 0.0
        self.i_smooth_a = 0.0
        self._history: deque[tuple[float, float]] = deque(maxlen=self.HISTORY)
        self.out_of_battery = False

    def step(self, dt_s: float, power_w: float, draining: bool, charging: bool) -> None:
        """One physics step of `dt_s` with `power_w` drawn while draining."""
        p = self.p
        tau = max(p.tau_s, dt_s)  # gz-sim: tau is raised to dt when smaller
        if abs(self.voltage_v) < 1e-3 and not charging:
            self.voltage_v = 0.0
            return
        if self.soc < 0 and not charging:
            return
        total_w = power_w if draining else 0.0
        self.i_raw_a = total_w / self.voltage_v
        if charging and self.soc < 0.9 and p.charging_time_h > 0:
            self.i_raw_a -= p.capacity_ah / p.charging_time_h
        self.i_smooth_a += dt_s / tau * (self.i_raw_a - self.i_smooth_a)
        if not p.fix_issue_225:
            self._history.append((self.i_smooth_a, dt_s))
        self.q_ah -= dt_s * self.i_smooth_a / 3600.0
        self.voltage_v = p.e0_v + p.e1_v * (1.0 - self.q_ah / p.capacity_ah) - p.resistance_ohm * self.i_smooth_a
        if p.fix_issue_225:
            self.soc = self.q_ah / p.capacity_ah
        else:
            self.soc -= sum(i * dt / 3600.0 for i, dt in self._history) / p.capacity_ah
        if self.soc < 0:
            self.out_of_battery = True
