"""rclpy.destroyable: the protocol of entities that can be destroyed once no callback uses them."""

from __future__ import annotations

import weakref
from types import TracebackType
from typing import Any, Protocol

from diffctl.client.exceptions import InvalidHandle


class DestroyableType(Protocol):
    def __enter__(self) -> None: ...

    def __exit__(self, exc_type: type[BaseException] | None, exc_val: BaseException | None,
                 exctb: TracebackType | None) -> None: ...

    def destroy_when_not_in_use(self) -> None: ...


class Handle:
    """What an entity's `handle` property answers (rclpy's are pybind11 objects): a `with` block on it is
    allowed while its entity lives; once the entity was destroyed, or the handle asked to be, entering it raises
    InvalidHandle. The entity is held weakly, so a handle kept by user code keeps no node alive."""

    __slots__ = ("__weakref__", "_owner", "_requested")

    def __init__(self, owner: object) -> None:
        self._owner = weakref.ref(owner)
        self._requested = False

    def _valid(self) -> bool:
        owner = self._owner()
        return owner is not None and not self._requested and not getattr(owner, "_destroyed", False)

    def __enter__(self) -> None:
        if not self._valid():
            raise InvalidHandle("cannot use Destroyable because destruction was requested")

    def __exit__(self, exc_type: type[BaseException] | None, exc_val: BaseException | None,
                 exctb: TracebackType | None) -> None:
        pass

    def destroy_when_not_in_use(self) -> None:
        self._requested = True


def handle_of(owner: Any) -> Handle:
    """`owner`'s one handle, made the first time it is asked for."""
    handle = owner.__dict__.get("_handle")
    if handle is None:
        handle = owner.__dict__["_handle"] = Handle(owner)
    return handle
