"""rclpy.context.Context: init once, shutdown once, shutdown callbacks; the process's default context."""

from __future__ import annotations

import os
import threading
import weakref
from collections.abc import Callable
from typing import Any

from diffctl.client import waiting
from diffctl.client.destroyable import Handle, handle_of
from diffctl.client.exceptions import RCLError
from diffctl.errors import ConfigError


class Context:
    """One ROS "init": its arguments, domain and whether it is still ok."""

    def __init__(self) -> None:
        self._lock = threading.RLock()
        self._callbacks: list[Any] = []
        self._init_called = False
        self._ok = False
        self._args: list[str] = []
        self._domain_id: int | None = None
        self._nodes: weakref.WeakSet[Any] = weakref.WeakSet()
        self._destroyed = False

    def __enter__(self) -> Context:
        self.init()
        return self

    def __exit__(self, *exc: Any) -> None:
        self.try_shutdown()

    @property
    def handle(self) -> Handle | None:
        """None until init(), as rclpy's (its rcl context is made there); valid until destroy()."""
        return handle_of(self) if self._init_called else None

    def init(self, args: list[str] | None = None, *, initialize_logging: bool = True,
             domain_id: int | None = None) -> None:
        import sys

        from diffctl.bus.session import domain_id as env_domain

        with self._lock:
            if self._init_called:
                raise RuntimeError("Context.init() must only be called once")
            if domain_id is not None and not (isinstance(domain_id, int) and domain_id >= 0):
                raise RuntimeError(f"Domain ID must be a non-negative integer, got {domain_id!r}")
            argv = list(sys.argv if args is None else args)
            for a in argv:
                a.encode("utf-8")  # rcl takes C strings: a lone surrogate (an undecodable byte) fails as in rclpy
            _check_ros_args(argv)
            self._args = argv
            self._domain_id = env_domain() if domain_id is None else domain_id
            if domain_id is not None:
                # The process's one Zenoh session reads its domain where nodes are made: an explicit domain
                # is this process's ROS_DOMAIN_ID from here on (its children inherit it, as with the variable).
                os.environ["ROS_DOMAIN_ID"] = str(domain_id)
            self._init_called = True
            self._ok = True
        from diffctl.client import ros_logging

        ros_logging.configure_from_args(self._args)

    @property
    def args(self) -> list[str]:
        return list(self._args)

    def ok(self) -> bool:
        return self._ok

    def _call_on_shutdown(self) -> None:
        for cb in self._callbacks:
            fn = cb() if isinstance(cb, weakref.WeakMethod) else cb
            if fn is not None:
                fn()
        self._callbacks = []

    def shutdown(self) -> None:
        with self._lock:
            if not self._ok:
                if not self._init_called:
                    raise RuntimeError("Context must be initialized before it can be shutdown")
                raise RCLError("failed to shutdown: rcl_shutdown already called on the given context, "
                               "at /project/src/rcl/init.c:333")
            self._ok = False
            self._call_on_shutdown()
        waiting.notify()

    def try_shutdown(self) -> None:
        with self._lock:
            if self._ok:
                self.shutdown()

    def on_shutdown(self, callback: Callable[[], None]) -> None:
        if not callable(callback):
            raise TypeError("callback should be a callable, got {}", type(callback))
        with self._lock:
            if not self._ok:
                callback()
            else:
                try:
                    self._callbacks.append(weakref.WeakMethod(callback))  # type: ignore[arg-type]
                except TypeError:
                    self._callbacks.append(callback)

    def get_domain_id(self) -> int:
        with self._lock:
            if self._domain_id is None:
                from diffctl.bus.session import domain_id

                return domain_id()
            return self._domain_id

    def track_node(self, node: Any) -> None:
        self._nodes.add(node)

    def untrack_node(self, node: Any) -> None:
        self._nodes.discard(node)

    def destroy(self) -> None:
        self.try_shutdown()
        self._destroyed = True


_default_context: Context | None = None
_default_lock = threading.Lock()
_all_contexts: weakref.WeakSet[Context] = weakref.WeakSet()


class _InitArgumentsError(RCLError, ConfigError):
    """rclpy's init fails on a malformed --ros-args rule with a plain RCLError; diffctl's ConfigError too, so a
    component started with one ends with a one-line message and exit code 2."""

    def __init__(self, message: str) -> None:
        ConfigError.__init__(self, message)


# A traceback names it as rclpy's plain RCLError (`rclpy._rclpy_pybind11.RCLError: failed to initialize rcl: …`).
# type(e).__name__ too, as a program printing the type of what init raised shows it.
_InitArgumentsError.__module__, _InitArgumentsError.__qualname__ = "rclpy._rclpy_pybind11", "RCLError"
_InitArgumentsError.__name__ = "RCLError"


def _check_ros_args(argv: list[str]) -> None:
    """rcl's init reads the process's --ros-args: a malformed rule fails it, then unknown arguments do."""
    from diffctl import ros_args
    from diffctl.client.exceptions import UnknownROSArgsError

    try:
        ros_args.check(ros_args.split_argv(argv)[1])
    except ros_args.UnknownRosArgsError as e:
        raise UnknownROSArgsError(str(e.unknown)) from None
    except ConfigError as e:
        raise _InitArgumentsError(f"failed to initialize rcl: {e}") from None


def get_default_context(*, shutting_down: bool = False) -> Context:
    """The process's default context; `shutting_down` hands it over and forgets it (a later init makes anew)."""
    global _default_context
    with _default_lock:
        if _default_context is None:
            _default_context = Context()
            _all_contexts.add(_default_context)
        ctx = _default_context
        if shutting_down:
            _default_context = None
        return ctx


def track(context: Context) -> None:
    _all_contexts.add(context)


def all_contexts() -> list[Context]:
    return list(_all_contexts)
