"""Gazebo's LinearBatteryPlugin system (`gz-sim-linearbatteryplugin-system`): a battery drained by a constant
power load, its state as gz.msgs.BatteryState on `/model/<model>/battery/<battery_name>/state` (50 Hz).

Parameters as gz-sim 8 reads them: `<battery_name>`, `<voltage>`, `<capacity>` (Ah, > 0) required;
`<open_circuit_voltage_constant_coef>`, `<open_circuit_voltage_linear_coef>`, `<initial_charge>` (clamped to
[0, capacity]), `<resistance>`, `<smooth_current_tau>`, `<power_load>` (W), `<start_draining>`,
`<power_draining_topic>` / `<stop_power_draining_topic>` (repeatable; any message starts / stops draining),
`<enable_recharge>` with `<charging_time>` (h): the services `/model/<model>/battery/<name>/recharge/start|stop`
(gz.msgs.Boolean → gz.msgs.Empty, any request starts / stops charging), and with `<recharge_by_topic>` also
Boolean messages on those names as topics, `<fix_issue_225>` (percentage 0–100 and soc = q / c),
`<invert_current_sign>`.
Draining also starts, and stays on, once any joint of the model is commanded a non-zero velocity or effort.
Status: CHARGING, else DISCHARGING, else FULL above 90 %, else NOT_CHARGING.
"""

from __future__ import annotations

from collections.abc import Callable

from diffctl.bus import gz
from diffctl.description.model import Plugin
from diffctl.errors import DescriptionError
from diffctl.sim.entity import Entity
from diffctl.sim.plugins.base import PluginContext, SystemPlugin, bool_param, float_param, rate_period_ns
from diffctl.sim.plugins.battery_model import BatteryParams, LinearBattery

STATE_RATE_HZ = 50.0


def battery_params(plugin: Plugin, source: str = "") -> BatteryParams:
    def need(tag: str) -> str:
        text = plugin.get(tag)
        if text is None or not text.strip():
            raise DescriptionError(
                f"plugin {plugin.name!r}: <{tag}> is required",
                source=source or None,
                field=f"plugin {plugin.filename}: {tag}",
                hint="LinearBatteryPlugin needs <battery_name>, <voltage> and <capacity>",
            )
        return text.strip()

    name = need("battery_name")
    need("voltage")
    need("capacity")
    voltage = float_param(plugin, "voltage", None, source=source)
    capacity = float_param(plugin, "capacity", None, source=source, positive=True)
    assert voltage is not None and capacity is not None
    q0 = float_param(plugin, "initial_charge", capacity, source=source)
    tau = float_param(plugin, "smooth_current_tau", 1.0, source=source)
    recharge = bool_param(plugin, "enable_recharge", False, source=source)
    charging_time = float_param(plugin, "charging_time", None, source=source)
    if recharge and charging_time is None:
        raise DescriptionError(
            f"plugin {plugin.name!r}: <enable_recharge> needs <charging_time> (hours)",
            source=source or None,
            field=f"plugin {plugin.filename}: charging_time",
        )
    return BatteryParams(
        name=name,
        voltage_v=voltage,
        capacity_ah=capacity,
        initial_charge_ah=min(max(q0 or 0.0, 0.0), capacity),
        e0_v=float_param(plugin, "open_circuit_voltage_constant_coef", 0.0, source=source) or 0.0,
        e1_v=float_param(plugin, "open_circuit_voltage_linear_coef", 0.0, source=source) or 0.0,
        resistance_ohm=float_param(plugin, "resistance", 0.0, source=source) or 0.0,
        tau_s=tau if tau is not None and tau > 0 else 1.0,
        charging_time_h=(charging_time or 0.0) if recharge else 0.0,
        fix_issue_225=bool_param(plugin, "fix_issue_225", False, source=source),
    )


class LinearBatteryPlugin(SystemPlugin):
    def __init__(self, ctx: PluginContext, entity: Entity, plugin: Plugin) -> None:
        self.ctx, self.entity = ctx, entity
        source = entity.model.source
        self.battery = LinearBattery(battery_params(plugin, source))
        self.power_w = float_param(plugin, "power_load", 0.0, source=source) or 0.0
        if plugin.get("power_load") is None:
            ctx.log.warn(f"model {entity.name!r}: LinearBatteryPlugin without <power_load>: the battery never drains")
        self.start_draining = bool_param(plugin, "start_draining", False, source=source)
        self.invert_current = bool_param(plugin, "invert_current_sign", False, source=source)
        self.draining = self.start_draining
        self.charging = False
        self._motion_seen = entity.motion_commands
        name = self.battery.p.name
        self.topic = f"/model/{entity.name}/battery/{name}/state"
        self.topics = (self.topic,)
        self.last_message: dict | None = None
        self._warned_empty = False
        t = ctx.transport
        self._owned: list = []
        self._pub = t.publisher(self.topic, "gz.msgs.BatteryState") if t else None
        if t is not None:
            for topic in plugin.get_all("power_draining_topic"):
                self._owned.append(t.raw_subscribe(gz.key(topic), lambda _s: ctx.stepper.call_soon(self._drain)))
            for topic in plugin.get_all("stop_power_draining_topic"):
                self._owned.append(t.raw_subscribe(gz.key(topic), lambda _s: ctx.stepper.call_soon(self._stop)))
            base = f"/model/{entity.name}/battery/{name}/recharge"
            if self.battery.p.charging_time_h > 0:
                for leaf, on in (("start", True), ("stop", False)):
                    self._owned.append(
                        t.gz_service(f"{base}/{leaf}", "gz.msgs.Boolean", "gz.msgs.Empty", self._recharge_service(on))
                    )
            if self.battery.p.charging_time_h > 0 and plugin.get("recharge_by_topic") is not None:
                self._owned.append(t.subscribe(f"{base}/start", "gz.msgs.Boolean", lambda _m: self._recharge(True)))
                self._owned.append(t.subscribe(f"{base}/stop", "gz.msgs.Boolean", lambda _m: self._recharge(False)))
        self._dt_s = ctx.stepper.step_ns * 1e-9
        ctx.stepper.step_hooks.append(self._step)
        period = rate_period_ns(STATE_RATE_HZ, ctx.stepper.step_ns)
        self._task = ctx.stepper.add_task(f"battery:{entity.name}:{name}", period, self._publish)

    def _drain(self) -> None:
        self.draining = True

    def _stop(self) -> None:
        self.draining = False

    def _recharge(self, on: bool) -> None:
        self.charging = on

    def _recharge_service(self, on: bool) -> Callable[[dict], dict]:
        def handle(_request: dict) -> dict:
            self._recharge(on)
            return {}

        return handle

    def _step(self) -> None:
        if not self.draining and self.entity.motion_commands != self._motion_seen:
            self.draining = True  # gz-sim: a non-zero joint velocity or force command starts draining
        self._motion_seen = self.entity.motion_commands
        if self.draining or self.charging:
            self.battery.step(self._dt_s, self.power_w, self.draining, self.charging)
            if self.battery.out_of_battery and not self._warned_empty:
                self._warned_empty = True
                self.ctx.log.warn(f"Model {self.entity.name} out of battery.")

    def message(self, sim_time_ns: int) -> dict:
        b = self.battery
        if self.charging:
            status = "CHARGING"
        elif self.draining:
            status = "DISCHARGING"
        elif b.soc > 0.9:
            status = "FULL"
        else:
            status = "NOT_CHARGING"
        return {
            "header": gz.header(sim_time_ns),
            "voltage": b.voltage_v,
            "current": -b.i_smooth_a if self.invert_current else b.i_smooth_a,
            "charge": b.q_ah,
            "capacity": b.p.capacity_ah,
            "percentage": b.soc * 100.0 if b.p.fix_issue_225 else b.soc,
            "power_supply_status": status,
        }

    def _publish(self, sim_time_ns: int) -> None:
        self.last_message = msg = self.message(sim_time_ns)
        if self._pub is not None and self._pub.matched:
            self._pub.publish(msg)

    def reset(self) -> None:
        self.battery.reset()
        self.draining = self.start_draining
        self.charging = False
        self._motion_seen = self.entity.motion_commands

    def close(self) -> None:
        self.ctx.stepper.remove_task(self._task)
        if self._step in self.ctx.stepper.step_hooks:
            self.ctx.stepper.step_hooks.remove(self._step)
        t = self.ctx.transport
        if t is not None:
            for obj in (self._pub, *self._owned):
                if obj is not None:
                    t.release(obj)
