"""Talking to a running simulator's world services from another process (spawn, control, state).

Light on purpose: no physics import, so `diffctl spawn entity` and `diffctl sim state` start fast.
"""

from __future__ import annotations

import json
import time
from typing import Any

from diffctl.errors import RuntimeFailure
from diffctl.sim.world_keys import SIM_TOKEN_PATTERN, sim_token_key, world_key


def running_worlds(session: Any, world: str | None = None) -> list[str]:
    pattern = sim_token_key(world) if world else SIM_TOKEN_PATTERN
    replies = session.liveliness().get(pattern, timeout=0.5)
    return sorted({str(r.ok.key_expr).split("/")[2] for r in replies if r.ok is not None})


def wait_for_world(session: Any, world: str | None, deadline: float) -> str:
    """The one world a simulator runs (or `world`), waiting for it until `deadline` (time.monotonic)."""
    while True:
        worlds = running_worlds(session, world)
        if len(worlds) == 1:
            return worlds[0]
        if len(worlds) > 1:
            raise RuntimeFailure(f"several simulators run worlds {', '.join(worlds)}", hint="choose one with --world")
        if time.monotonic() > deadline:
            what = f"world {world!r}" if world else "any world"
            raise RuntimeFailure(f"no simulator runs {what}", hint="start one with `diffctl sim run -r WORLD`")
        time.sleep(0.1)


def call(session: Any, world: str, service: str, req: dict[str, Any], deadline: float) -> dict[str, Any]:
    """One world service call; a refusal raises RuntimeFailure with the simulator's reason."""
    key = world_key(world, service)
    timeout = max(1.0, deadline - time.monotonic())
    for r in session.get(key, payload=json.dumps(req).encode(), timeout=timeout):
        if r.ok is None:
            continue
        try:
            body = json.loads(r.ok.payload.to_bytes())
        except ValueError:
            raise RuntimeFailure(f"{key}: malformed reply") from None
        if not body.get("ok"):
            raise RuntimeFailure(f"{service} failed: {body.get('error', 'no reason given')}")
        return body
    raise RuntimeFailure(f"the simulator did not answer {key} in time")
