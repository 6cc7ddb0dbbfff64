"""Transitional: venvs installed before the interfaces moved to `diffctl.interfaces` keep a copy of the old
import hook, which asks `diffctl.client.messages.finder`; `make .venv/.installed` replaces that copy. Goes with
the bus node's removal."""

from diffctl.interfaces import finder  # noqa: F401
