"""rclpy.lifecycle's ManagedEntity, SimpleManagedEntity, LifecyclePublisher and TransitionCallbackReturn."""

from __future__ import annotations

import enum
from collections.abc import Callable
from functools import wraps
from typing import Any

from diffctl.client.lifecycle.state_machine import ERROR_LABEL, FAILURE_LABEL, SUCCESS_LABEL
from diffctl.client.publisher import Publisher


class TransitionCallbackReturnType(enum.Enum):
    """What a transition callback returns. As rclpy's (a pybind11 enum): not equal to its int."""

    SUCCESS = 97
    FAILURE = 98
    ERROR = 99

    def __int__(self) -> int:
        return self.value

    def __index__(self) -> int:
        return self.value

    def __str__(self) -> str:
        return f"TransitionCallbackReturnType.{self.name}"

    def __repr__(self) -> str:
        return f"<TransitionCallbackReturnType.{self.name}: {self.value}>"

    def to_label(self) -> str:
        return {97: SUCCESS_LABEL, 98: FAILURE_LABEL, 99: ERROR_LABEL}[self.value]


TransitionCallbackReturn = TransitionCallbackReturnType


class ManagedEntity:
    """An entity a lifecycle node moves through its transitions (each default callback succeeds)."""

    def on_configure(self, state: Any) -> TransitionCallbackReturn:
        return TransitionCallbackReturn.SUCCESS

    def on_cleanup(self, state: Any) -> TransitionCallbackReturn:
        return TransitionCallbackReturn.SUCCESS

    def on_shutdown(self, state: Any) -> TransitionCallbackReturn:
        return TransitionCallbackReturn.SUCCESS

    def on_activate(self, state: Any) -> TransitionCallbackReturn:
        return TransitionCallbackReturn.SUCCESS

    def on_deactivate(self, state: Any) -> TransitionCallbackReturn:
        return TransitionCallbackReturn.SUCCESS

    def on_error(self, state: Any) -> TransitionCallbackReturn:
        return TransitionCallbackReturn.SUCCESS


class SimpleManagedEntity(ManagedEntity):
    """Enabled between activate and deactivate."""

    def __init__(self) -> None:
        self._enabled = False

    def on_activate(self, state: Any) -> TransitionCallbackReturn:
        self._enabled = True
        return TransitionCallbackReturn.SUCCESS

    def on_deactivate(self, state: Any) -> TransitionCallbackReturn:
        self._enabled = False
        return TransitionCallbackReturn.SUCCESS

    @property
    def is_activated(self) -> bool:
        return self._enabled

    @staticmethod
    def when_enabled(wrapped: Callable[..., Any] | None = None, *,
                     when_not_enabled: Callable[[], None] | None = None) -> Any:
        """Decorate a method so it does nothing (but call `when_not_enabled`) while not activated."""

        def decorator(method: Callable[..., Any]) -> Callable[..., Any]:
            @wraps(method)
            def only_when_enabled(self: SimpleManagedEntity, *args: Any, **kwargs: Any) -> Any:
                if not self._enabled:
                    if when_not_enabled is not None:
                        when_not_enabled()
                    return None
                return method(self, *args, **kwargs)

            return only_when_enabled

        return decorator if wrapped is None else decorator(wrapped)


class LifecyclePublisher(SimpleManagedEntity, Publisher):
    """A publisher whose publish() is silently dropped unless its node is active."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        SimpleManagedEntity.__init__(self)
        Publisher.__init__(self, *args, **kwargs)

    @SimpleManagedEntity.when_enabled
    def publish(self, msg: Any) -> None:
        Publisher.publish(self, msg)
