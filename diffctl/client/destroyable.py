"""rclpy.destroyable: the protocol of entities that can be destroyed once no callback uses them."""

from __future__ import annotations

from types import TracebackType
from typing import Protocol


class DestroyableType(Protocol):
    def __enter__(self) -> None: ...

    def __exit__(self, exc_type: type[BaseException] | None, exc_val: BaseException | None,
                 exctb: TracebackType | None) -> None: ...

    def destroy_when_not_in_use(self) -> None: ...
