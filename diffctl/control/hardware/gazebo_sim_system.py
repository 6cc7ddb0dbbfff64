"""gz_ros2_control/GazeboSimSystem: hardware whose joints live in the simulator, driven in lockstep on sim time.

Protocol (diffctl/bus/hw_endpoint.py): the hardware waits for the model's endpoint token (the simulator may
start later), reads its joint list from `info`, and on activation attaches with the manager's update_rate
and declares the manager token. From then on every state sample (tick n, sim time) drives one manager
cycle — this component is the loop's ticker — and write() answers it with the command for tick n; a cycle
that wrote nothing (hardware inactive) still answers with "no command", so the simulator never waits in vain.
Commands follow gz_ros2_control: the claimed mode per joint (velocity, position or effort) is sent, the
rest NaN (held by the simulator). Non-finite commands never leave the manager; commands are clamped to
the interface's min/max when the <ros2_control> block gives them.
"""

from __future__ import annotations

import json
import math
import queue
import threading
import time
from typing import Any

import numpy as np

from diffctl.bus import hw_endpoint as hw
from diffctl.control.controller_interface import CommandInterface, ReturnType, StateInterface
from diffctl.control.hardware_interface import HardwareComponent, HardwareInfo
from diffctl.errors import ConfigError, RuntimeFailure

_MODES = ("velocity", "position", "effort")
_WAIT_LOG_S = 5.0


def _query_json(session: Any, key: str, body: dict[str, Any] | None = None, timeout_s: float = 2.0) -> Any:
    payload = json.dumps(body or {}).encode()
    for r in session.get(key, payload=payload, timeout=timeout_s):
        if r.ok is not None:
            return json.loads(r.ok.payload.to_bytes())
        raise RuntimeFailure(f"{key}: {r.err.payload.to_string()}")
    raise RuntimeFailure(f"{key}: no answer within {timeout_s:g} s")


class GazeboSimSystem(HardwareComponent):
    # --- finding the endpoint -----------------------------------------------------------------------
    def on_init(self, info: HardwareInfo) -> None:
        super().on_init(info)
        from diffctl.bus import open_session

        self.session = open_session()
        self.joints = [j.name for j in info.joints]
        self.model = self._find_model(info.hardware_parameters.get("model") or None)
        ep = _query_json(self.session, hw.info_key(self.model))
        ep_joints = {j["name"]: j for j in ep.get("joints", [])}
        missing = [j for j in self.joints if j not in ep_joints]
        if missing:
            raise ConfigError(
                f"model {self.model!r} has no ros2_control joints {missing} (it has {sorted(ep_joints)})",
                source=info.source,
            )
        self.order = [j["name"] for j in ep["joints"]]
        self.index = {name: self.order.index(name) for name in self.joints}
        self.initial = {name: ep_joints[name].get("initial", {}) for name in self.joints}
        self.mode: dict[str, str | None] = {name: None for name in self.joints}
        self.sample: hw.State | None = None
        self._answered = True
        self._queue: queue.SimpleQueue[hw.State] = queue.SimpleQueue()
        self._declared: list[Any] = []
        self._attached = False
        self.control_period_ns = 0
        self.missed_logs = 0
        self._log("info", f"found the simulator's ros2_control endpoint for model {self.model!r}")

    def _log(self, level: str, text: str) -> None:
        if self.log is not None:
            getattr(self.log, level)(f"{self.name}: {text}")

    def _cancelled(self) -> bool:
        return self.cancel is not None and self.cancel.is_set()

    def _find_model(self, wanted: str | None) -> str:
        start = last_log = time.monotonic()
        said = False
        while True:
            models = hw.endpoint_models(self.session, timeout=0.5)
            if wanted is not None and wanted in models:
                return wanted
            if wanted is None and models:
                matching = [m for m in models if self._joints_match(m)]
                if len(matching) == 1:
                    return matching[0]
                if len(matching) > 1:
                    raise ConfigError(
                        f"several simulator models have the joints of <ros2_control name="
                        f"{self.name!r}>: {', '.join(matching)}",
                        hint="pick one with --model NAME",
                    )
            if not said or time.monotonic() - last_log > _WAIT_LOG_S:
                what = f"model {wanted!r}" if wanted else f"a model with joints {self.joints}"
                seen = f" (endpoints now: {', '.join(models)})" if models else ""
                self._log(
                    "info" if not said else "warn",
                    f"waiting for the simulator's ros2_control endpoint of {what}{seen}… "
                    f"{time.monotonic() - start:.0f} s",
                )
                said, last_log = True, time.monotonic()
            if self._cancelled():
                raise RuntimeFailure("stopped while waiting for the simulator")
            time.sleep(0.2)

    def _joints_match(self, model: str) -> bool:
        try:
            ep = _query_json(self.session, hw.info_key(model), timeout_s=1.0)
        except (RuntimeFailure, ValueError):
            return False
        names = {j.get("name") for j in ep.get("joints", [])}
        return set(self.joints) <= names

    # --- interfaces ---------------------------------------------------------------------------------
    def export_state_interfaces(self) -> list[StateInterface]:
        out = super().export_state_interfaces()
        for it in out:
            joint, _, iface = it.name.rpartition("/")
            it.value = float(self.initial.get(joint, {}).get(iface, 0.0))
        return out

    def export_command_interfaces(self) -> list[CommandInterface]:
        out = super().export_command_interfaces()
        for it in out:
            it.value = math.nan
        return out

    def perform_command_mode_switch(self, start: list[str], stop: list[str]) -> bool:
        for name in stop:
            joint = name.rpartition("/")[0]
            if joint in self.mode:
                self.mode[joint] = None
        for name in start:
            joint, _, iface = name.rpartition("/")
            if joint in self.mode and iface in _MODES:
                self.mode[joint] = iface
        return True

    def prepare_command_mode_switch(self, start: list[str], stop: list[str]) -> bool:
        per_joint: dict[str, int] = {}
        for name in start:
            joint, _, iface = name.rpartition("/")
            if iface in _MODES:
                per_joint[joint] = per_joint.get(joint, 0) + 1
        return all(n <= 1 for n in per_joint.values())

    # --- lifecycle: attach / detach ------------------------------------------------------------------
    def on_activate(self) -> None:
        self._attach()

    def _attach(self) -> None:
        self._detach()
        rate = self.update_rate or 100
        self._declared.append(self.session.declare_subscriber(hw.state_key(self.model), self._on_state))
        self._pub = self.session.declare_publisher(hw.command_key(self.model))
        self._declared.append(self._pub)
        self._declared.append(self.session.liveliness().declare_token(hw.manager_key(self.model)))
        reply = _query_json(
            self.session, hw.attach_key(self.model), {"update_rate": rate, "manager": f"{self.name}@{id(self):x}"}
        )
        if not reply.get("ok"):
            self._detach()
            raise RuntimeFailure(f"the simulator refused to attach model {self.model!r}: {reply.get('error')}")
        self.control_period_ns = int(reply.get("control_period_ns") or 1e9 / rate)
        self._attached = True
        self._log(
            "info", f"attached to model {self.model!r}: lockstep every {self.control_period_ns / 1e6:g} ms of sim time"
        )

    def _detach(self) -> None:
        for obj in reversed(self._declared):
            try:
                obj.undeclare()
            except Exception:
                pass
        self._declared = []
        self._attached = False

    def on_deactivate(self) -> None:
        self._answer_nan()
        self._detach()

    def on_shutdown(self) -> None:
        self._detach()

    def on_error(self) -> None:
        self._answer_nan()
        self._detach()

    def _on_state(self, sample: Any) -> None:
        try:
            self._queue.put(hw.decode_state(sample.payload.to_bytes()))
        except Exception as e:
            self._log("warn", f"dropped a malformed state sample: {e}")

    # --- the loop's ticker -----------------------------------------------------------------------------
    def ticker(self) -> GazeboSimSystem:
        return self

    def wait(self, stop: threading.Event) -> tuple[int, float] | None:
        waited = 0.0
        while not stop.is_set():
            try:
                s = self._queue.get(timeout=0.1)
            except queue.Empty:
                waited += 0.1
                if waited >= _WAIT_LOG_S and self._attached:
                    waited = 0.0
                    self.missed_logs += 1
                    models = hw.endpoint_models(self.session, timeout=0.3)
                    if self.model not in models:
                        self._log("warn", f"the simulator's endpoint for {self.model!r} is gone; waiting for it")
                    else:
                        self._log("warn", f"no state from the simulator for {_WAIT_LOG_S:g} s (paused?); re-attaching")
                        try:
                            self._attach()
                        except Exception as e:
                            self._log("warn", f"re-attach failed: {e}")
                continue
            while True:  # keep only the newest (the sim waits for each answer, so backlog = stale ticks)
                try:
                    s = self._queue.get_nowait()
                except queue.Empty:
                    break
            prev = self.sample
            self.sample = s
            self._answered = False
            if prev is not None and s.sim_time_ns > prev.sim_time_ns:
                period = (s.sim_time_ns - prev.sim_time_ns) / 1e9
            else:
                period = (self.control_period_ns or 1e9 / max(self.update_rate, 1)) / 1e9
            return s.sim_time_ns, period
        return None

    def cycle_done(self) -> None:
        if not self._answered:
            self._answer_nan()

    def _answer_nan(self) -> None:
        s = self.sample
        if s is None or self._answered or not self._attached:
            return
        n = len(self.order)
        try:
            self._pub.put(hw.encode_command(s.tick, np.full(n, np.nan), np.full(n, np.nan), np.full(n, np.nan)))
        except Exception:
            pass
        self._answered = True

    # --- real-time ------------------------------------------------------------------------------------
    def read(self, time_ns: int, period_s: float) -> ReturnType:
        s = self.sample
        if s is None:
            return ReturnType.OK
        states = self.states
        for joint, i in self.index.items():
            for iface, arr in (("position", s.position), ("velocity", s.velocity), ("effort", s.effort)):
                it = states.get(f"{joint}/{iface}")
                if it is not None and iface != "effort":  # gz_ros2_control never updates effort
                    it.value = float(arr[i])
        return ReturnType.OK

    def write(self, time_ns: int, period_s: float) -> ReturnType:
        s = self.sample
        if s is None or self._answered or not self._attached:
            return ReturnType.OK
        n = len(self.order)
        out = {m: np.full(n, np.nan) for m in _MODES}
        for joint, mode in self.mode.items():
            if mode is None:
                continue
            cmd = self.commands.get(f"{joint}/{mode}")
            if cmd is None:
                continue
            v = cmd.value
            if not math.isfinite(v):
                continue  # NaN = no command (held); inf never reaches the physics
            lim = self._limits(joint, mode)
            out[mode][self.index[joint]] = min(max(v, lim[0]), lim[1])
        self._pub.put(hw.encode_command(s.tick, out["velocity"], out["position"], out["effort"]))
        self._answered = True
        return ReturnType.OK

    def _limits(self, joint: str, mode: str) -> tuple[float, float]:
        for j in self.info.joints:
            if j.name == joint:
                for c in j.command_interfaces:
                    if c.name == mode:
                        return c.min, c.max
        return -math.inf, math.inf
