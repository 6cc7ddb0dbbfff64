"""The spawner a launch context starts processes with (diffctl's supervision)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..launch_context import LaunchContext


def spawner_for(context: LaunchContext) -> Any:
    """The context's spawner: the one its LaunchService was given, else a `PosixSpawner` made for it."""
    spawner = getattr(context, '_spawner', None)
    if spawner is None:
        from diffctl.supervision import PosixSpawner

        from .. import logging as launch_logging

        spawner = context._spawner = PosixSpawner(logger=launch_logging.get_logger('launch.supervision'))
    return spawner
