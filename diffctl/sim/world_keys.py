"""Zenoh keys of a simulated world's services and presence token (light: no physics import)."""

from __future__ import annotations


def world_key(world: str, leaf: str) -> str:
    """`gz/world/<world>/<leaf>`: control, create, remove, state."""
    return f"gz/world/{world}/{leaf}"


def sim_token_key(world: str) -> str:
    """The liveliness token a simulator declares while it runs `world`."""
    return world_key(world, "sim")


SIM_TOKEN_PATTERN = "gz/world/*/sim"
