"""The ros2_control hardware endpoint between the simulator and a controller manager: keys and binary codecs.

For a model M the simulator declares, while the endpoint exists:
  gz/model/M/ros2_control/endpoint   liveliness token (the endpoint is up)
  gz/model/M/ros2_control/info       queryable: JSON {"model", "joints": [{"name", "command_interfaces",
                                     "state_interfaces", "initial"}], "physics_step_s", "sim_time_ns"}
  gz/model/M/ros2_control/attach     queryable: the manager sends JSON {"update_rate": 20, "manager": "<id>"},
                                     the sim replies {"ok": true, "next_tick": n, "control_period_ns": p}
                                     or {"ok": false, "error": "..."}
  gz/model/M/ros2_control/state      sim → manager, one State sample every control period of sim time
The manager declares:
  gz/model/M/ros2_control/manager    liveliness token while attached (its disappearance = manager gone)
  gz/model/M/ros2_control/command    manager → sim, one Command sample answering each State (same tick)

Samples are little-endian binary (no JSON on the hot path):
  State:   tick u64, sim_time_ns i64, n u32, then float64[n] position, velocity, effort (joint order of `info`)
  Command: tick u64, n u32, then float64[n] velocity, position, effort commands; NaN = no command on that
           interface (the joint is held).
While a manager is attached the sim does not step past the next control boundary until the command for
that tick arrives (lockstep); see diffctl/sim/plugins/ros2_control.py for the sim side.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass
from typing import Any

import numpy as np

from diffctl.errors import MessageError

_STATE_HEAD = struct.Struct("<QqI")
_COMMAND_HEAD = struct.Struct("<QI")
_F64 = np.dtype("<f8")


def base_key(model: str) -> str:
    if not model or "/" in model or any(c in model for c in "*$?#"):
        raise MessageError(f"invalid model name {model!r} for a ros2_control endpoint (no '/', '*', '$', '?', '#')")
    return f"gz/model/{model}/ros2_control"


def endpoint_key(model: str) -> str:
    return f"{base_key(model)}/endpoint"


def info_key(model: str) -> str:
    return f"{base_key(model)}/info"


def attach_key(model: str) -> str:
    return f"{base_key(model)}/attach"


def manager_key(model: str) -> str:
    return f"{base_key(model)}/manager"


def state_key(model: str) -> str:
    return f"{base_key(model)}/state"


def command_key(model: str) -> str:
    return f"{base_key(model)}/command"


ENDPOINT_PATTERN = "gz/model/*/ros2_control/endpoint"


def model_of_key(key_expr: str) -> str | None:
    """The model name in any `gz/model/M/ros2_control/...` key, else None."""
    parts = str(key_expr).split("/")
    if len(parts) >= 4 and parts[0] == "gz" and parts[1] == "model" and parts[3] == "ros2_control":
        return parts[2]
    return None


def endpoint_models(session: Any, timeout: float = 1.0) -> list[str]:
    """Models that currently have a hardware endpoint (liveliness get on `gz/model/*/ros2_control/endpoint`)."""
    models: set[str] = set()
    for reply in session.liveliness().get(ENDPOINT_PATTERN, timeout=timeout):
        ok = getattr(reply, "ok", None)
        if ok is None:
            continue
        m = model_of_key(str(ok.key_expr))
        if m:
            models.add(m)
    return sorted(models)


@dataclass(frozen=True)
class State:
    tick: int
    sim_time_ns: int
    position: np.ndarray
    velocity: np.ndarray
    effort: np.ndarray


@dataclass(frozen=True)
class Command:
    tick: int
    velocity: np.ndarray
    position: np.ndarray
    effort: np.ndarray


def _arrays(n: int, *values: Any) -> list[np.ndarray]:
    out = []
    for v in values:
        a = np.full(n, np.nan) if v is None else np.asarray(v, dtype=_F64).reshape(-1)
        if a.shape[0] != n:
            raise MessageError(f"hardware endpoint sample: arrays of different lengths ({a.shape[0]} vs {n})")
        out.append(a)
    return out


def encode_state(tick: int, sim_time_ns: int, pos: Any, vel: Any, eff: Any) -> bytes:
    n = len(pos)
    p, v, e = _arrays(n, pos, vel, eff)
    return _STATE_HEAD.pack(tick, sim_time_ns, n) + p.tobytes() + v.tobytes() + e.tobytes()


def decode_state(b: bytes | bytearray | memoryview) -> State:
    b = bytes(b)
    if len(b) < _STATE_HEAD.size:
        raise MessageError(f"truncated hardware state sample: {len(b)} bytes, header needs {_STATE_HEAD.size}")
    tick, t_ns, n = _STATE_HEAD.unpack_from(b)
    need = _STATE_HEAD.size + 3 * 8 * n
    if len(b) != need:
        raise MessageError(f"truncated hardware state sample: {len(b)} bytes, {n} joints need {need}")
    data = np.frombuffer(b, dtype=_F64, offset=_STATE_HEAD.size, count=3 * n)
    return State(tick, t_ns, data[:n].copy(), data[n : 2 * n].copy(), data[2 * n :].copy())


def encode_command(tick: int, vel: Any, pos: Any = None, eff: Any = None) -> bytes:
    n = len(vel) if vel is not None else len(pos) if pos is not None else len(eff)
    v, p, e = _arrays(n, vel, pos, eff)
    return _COMMAND_HEAD.pack(tick, n) + v.tobytes() + p.tobytes() + e.tobytes()


def decode_command(b: bytes | bytearray | memoryview) -> Command:
    b = bytes(b)
    if len(b) < _COMMAND_HEAD.size:
        raise MessageError(f"truncated hardware command sample: {len(b)} bytes, header needs {_COMMAND_HEAD.size}")
    tick, n = _COMMAND_HEAD.unpack_from(b)
    need = _COMMAND_HEAD.size + 3 * 8 * n
    if len(b) != need:
        raise MessageError(f"truncated hardware command sample: {len(b)} bytes, {n} joints need {need}")
    data = np.frombuffer(b, dtype=_F64, offset=_COMMAND_HEAD.size, count=3 * n)
    return Command(tick, data[:n].copy(), data[n : 2 * n].copy(), data[2 * n :].copy())
