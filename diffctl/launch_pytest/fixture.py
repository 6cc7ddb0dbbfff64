"""`@launch_pytest.fixture` and the fixtures a launch test runs with: an asyncio event loop, the
LaunchService on it, and its context.

A launch fixture of a wider scope than a function (module, class, session) puts fixtures of that scope
named launch_service, event_loop and launch_context into its module, so its launch outlives one test.
"""

from __future__ import annotations

import asyncio
import sys
from collections.abc import Callable, Iterator
from typing import Any

import pytest

_SCOPES = ("function", "class", "module", "package", "session")


def _wider(scope: str, than: str) -> bool:
    return _SCOPES.index(scope) > _SCOPES.index(than)


def finalize_launch_service(launch_service: Any, eprefix: str = "", auto_shutdown: bool = True) -> None:
    """Shut the launch down (unless `auto_shutdown` is off) and run its loop until the launch has ended;
    a launch that ended with an error fails."""
    if auto_shutdown:
        launch_service.shutdown(force_sync=True)
    loop = launch_service.event_loop
    if loop is None or loop.is_closed():
        return
    rc = loop.run_until_complete(launch_service.task)
    assert rc == 0, f"{eprefix} launch service failed when finishing, return code '{rc}'"


def _overridable(fixture_function: Any, scope: str, overridable: bool) -> Any:
    if overridable:
        fixture_function._launch_pytest_overridable_fixture = True
        fixture_function._launch_pytest_fixture_scope = scope
    return fixture_function


def get_launch_service_fixture(*, scope: str = "function", overridable: bool = True) -> Any:
    """A `launch_service` fixture of `scope`: a LaunchService, finished at teardown."""

    @pytest.fixture(scope=scope)
    def launch_service(event_loop: Any) -> Iterator[Any]:
        from diffctl.launch import LaunchService

        service = LaunchService()
        yield service
        finalize_launch_service(service, eprefix="When tearing down launch_service fixture")

    return _overridable(launch_service, scope, overridable)


def get_launch_context_fixture(*, scope: str = "function", overridable: bool = True) -> Any:
    """A `launch_context` fixture of `scope`: the launch_service's LaunchContext."""

    @pytest.fixture(scope=scope)
    def launch_context(launch_service: Any) -> Any:
        return launch_service.context

    return _overridable(launch_context, scope, overridable)


def get_event_loop_fixture(*, scope: str = "function", overridable: bool = True) -> Any:
    """An `event_loop` fixture of `scope`: a new asyncio loop, the thread's current one until teardown."""

    @pytest.fixture(scope=scope)
    def event_loop() -> Iterator[asyncio.AbstractEventLoop]:
        loop = asyncio.new_event_loop()
        asyncio.set_event_loop(loop)
        yield loop
        loop.close()
        asyncio.set_event_loop(None)

    return _overridable(event_loop, scope, overridable)


_GETTERS: tuple[tuple[str, Callable[..., Any]], ...] = (
    ("launch_service", get_launch_service_fixture),
    ("event_loop", get_event_loop_fixture),
    ("launch_context", get_launch_context_fixture),
)


def _widen_module_fixtures(module_globals: dict[str, Any], scope: str) -> None:
    """A launch fixture of `scope` needs launch_service, event_loop and launch_context of (at least) that
    scope in its module; one the user wrote there is left alone."""
    for name, getter in _GETTERS:
        present = module_globals.get(name)
        if present is None or (getattr(present, "_launch_pytest_overridable_fixture", False)
              and _wider(scope, present._launch_pytest_fixture_scope)):
            module_globals[name] = getter(scope=scope)


def fixture(decorated: Any = None, *args: Any, shutdown_when_idle: bool = True, auto_shutdown: bool = True,
            **kwargs: Any) -> Any:
    """Mark a fixture returning a LaunchDescription (or a sequence starting with one) as a launch fixture;
    `args`/`kwargs` are pytest.fixture's. `shutdown_when_idle`: the launch ends by itself when nothing is left
    to do; `auto_shutdown`: it is shut down when its tests are done (else it must end by itself)."""
    scope = kwargs.get("scope", "function")
    if scope != "function":
        _widen_module_fixtures(sys._getframe(1).f_globals, scope)

    def decorator(fixture_function: Any) -> Any:
        fixture_function._launch_pytest_fixture = True
        fixture_function._launch_pytest_fixture_options = {
            "shutdown_when_idle": shutdown_when_idle,
            "auto_shutdown": auto_shutdown,
        }
        return pytest.fixture(*args, **kwargs)(fixture_function)

    return decorator if decorated is None else decorator(decorated)
