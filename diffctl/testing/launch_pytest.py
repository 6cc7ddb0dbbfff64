"""launch_pytest on diffctl's launch engine: `@launch_pytest.fixture` launch descriptions, `@pytest.mark.launch`
tests, and the `launch_service` / `launch_context` fixtures (pytest11 entry point `diffctl_launch_pytest`).

A launch fixture's description is launched (on a bus of its own, as every launch test here) when the fixture
is set up, and the fixture's value is available once its ReadyToTest was visited (one is appended when the
description has none); it is shut down at the fixture's teardown, failing it when the launch did not end
cleanly. A marked test gets the launch fixture set up first. Test bodies: plain functions run while the launch
does; `shutdown=True` shuts it down first; `async def` bodies run on an event loop of their own; a generator
body (async too) runs to its `yield`, then the launch is shut down (function-scoped fixtures) and the rest runs.
"""

from __future__ import annotations

import asyncio
import functools
import inspect
import threading
from typing import Any

import pytest

_SESSIONS: dict[str, LaunchSession] = {}
READY_TIMEOUT_S = 30.0


class LaunchSession:
    """One launch fixture's launch: its bus, its LaunchService, its ReadyToTest."""

    def __init__(self, description: Any, *, shutdown_when_idle: bool) -> None:
        from diffctl.launch_legacy.actions import LaunchDescription
        from diffctl.launch_legacy.event_handlers import OnProcessExit, OnProcessIO, RegisterEventHandler
        from diffctl.testing.decorators import ReadyToTest
        from diffctl.testing.handlers import cache_output, record_exit
        from diffctl.testing.isolation import isolated_bus
        from diffctl.testing.loader import find_ready_action
        from diffctl.testing.service import LaunchService

        self.ready = threading.Event()
        ready = find_ready_action(description)
        entities = [
            RegisterEventHandler(OnProcessExit(on_exit=lambda event, context: record_exit(event))),
            RegisterEventHandler(OnProcessIO(on_stdout=cache_output, on_stderr=cache_output)),
            description,
        ]
        if ready is None:
            ready = ReadyToTest()
            entities.append(ready)
        ready._add_callback(self.ready.set)
        self._bus = isolated_bus()
        self._bus.__enter__()
        self.service = LaunchService(LaunchDescription(entities), shutdown_when_idle=shutdown_when_idle,
                                     output_default="screen")
        self.after_shutdown: list[Any] = []

    def start(self) -> None:
        self.service.start()
        while not self.ready.wait(0.05):
            if not self.service.running:
                if self.service.error is not None:
                    raise self.service.error
                break
        if not self.ready.is_set() and self.service.error is not None:
            raise self.service.error

    def shutdown(self) -> int:
        self.service.shutdown()
        if not self.service.wait(30.0):
            self.service.kill()
            self.service.wait(5.0)
        if self.service.error is not None:
            raise self.service.error
        return self.service.return_code or 0

    def close(self) -> int:
        try:
            return self.shutdown()
        finally:
            self._bus.__exit__(None, None, None)


def _fixture_name(obj: Any) -> str | None:
    if isinstance(obj, str):
        return obj
    for candidate in (getattr(obj, "_launch_pytest_name", None), getattr(obj, "name", None)):
        if isinstance(candidate, str) and candidate:
            return candidate
    marker = getattr(obj, "_pytestfixturefunction", None)
    return getattr(marker, "name", None) or getattr(obj, "__name__", None)


def fixture(decorated: Any = None, *, shutdown_when_idle: bool = True, auto_shutdown: bool = True,
            **kwargs: Any) -> Any:
    """`@launch_pytest.fixture`: a pytest fixture returning a LaunchDescription (or a sequence whose first item
    is one); the description is running, past its ReadyToTest, when a test gets the value."""

    def decorator(fn: Any) -> Any:
        name = kwargs.get("name") or fn.__name__

        @functools.wraps(fn)
        def wrapper(*args: Any, **kw: Any) -> Any:
            value = fn(*args, **kw)
            description = value[0] if isinstance(value, (list, tuple)) else value
            session = LaunchSession(description, shutdown_when_idle=shutdown_when_idle)
            _SESSIONS[name] = session
            try:
                session.start()
                yield value
            finally:
                _SESSIONS.pop(name, None)
                code = session.close()
                errors = []
                for later in session.after_shutdown:
                    try:
                        later()
                    except BaseException as e:
                        errors.append(e)
                if errors:
                    raise errors[0]
                if code != 0:
                    raise AssertionError(f"launch service failed when finishing, return code '{code}'")

        wrapper.__signature__ = inspect.signature(fn)  # type: ignore[attr-defined]
        result = pytest.fixture(**kwargs)(wrapper)
        try:
            result._launch_pytest_name = name
        except AttributeError:
            pass
        return result

    return decorator(decorated) if decorated is not None else decorator


# ---- the plugin --------------------------------------------------------------------------------------------------


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line("markers", "launch(fixture, shutdown=False): a test run against a launch_pytest fixture")


def _has_launch_mark(obj: Any) -> bool:
    return any(getattr(m, "name", None) == "launch" for m in getattr(obj, "pytestmark", []))


@pytest.hookimpl(tryfirst=True)
def pytest_pycollect_makeitem(collector: Any, name: str, obj: Any) -> Any:
    """Generator tests are launch_pytest's way to test after shutdown: collected as tests when marked."""
    if (inspect.isgeneratorfunction(obj) or inspect.isasyncgenfunction(obj)) and _has_launch_mark(obj) \
            and collector.funcnamefilter(name):
        return list(collector._genfunctions(name, obj))
    return None


def _marker(item: Any) -> Any:
    return item.get_closest_marker("launch") if hasattr(item, "get_closest_marker") else None


def _marked_fixture(item: Any) -> str | None:
    mark = _marker(item)
    if mark is None:
        return None
    obj = mark.kwargs.get("fixture", mark.args[0] if mark.args else None)
    return _fixture_name(obj) if obj is not None else None


@pytest.hookimpl(trylast=True)  # after pytest grouped the items by their fixtures' parameters
def pytest_collection_modifyitems(session: pytest.Session, config: pytest.Config, items: list[Any]) -> None:
    _add_launch_fixtures(items)
    items[:] = _shutdown_tests_last(items)


def _launch_key(item: Any) -> tuple[str, str] | None:
    """(fixture, parameter) of a test on a launch that outlives it (a launch per test needs no ordering)."""
    name = _marked_fixture(item)
    if name is None or _function_scoped(item):
        return None
    callspec = getattr(item, "callspec", None)
    param = callspec.params.get(name, None) if callspec is not None else None
    return name, repr(param)


def _shutdown_tests_last(items: list[Any]) -> list[Any]:
    """In each run of items on one launch (fixture and parameter), the `shutdown=True` ones go last, as they
    end that launch."""
    out: list[Any] = []
    i = 0
    while i < len(items):
        key = _launch_key(items[i])
        j = i + 1
        while key is not None and j < len(items) and _launch_key(items[j]) == key:
            j += 1
        run = items[i:j]
        keep = [t for t in run if not _marker(t).kwargs.get("shutdown")] if key is not None else run
        out += keep + [t for t in run if t not in keep]
        if key is not None and any(_is_generator(t.obj) for t in run):
            last = run[-1]
            param = "" if key[1] == "None" else f"[{key[1].strip(chr(39))}]"
            label = f"{key[0]}{param}[shutdown_test]"
            out.append(ShutdownTestItem.from_parent(last.parent, name=label, fixture_name=key[0]))
        i = j
    return out


def _is_generator(fn: Any) -> bool:
    return inspect.isgeneratorfunction(fn) or inspect.isasyncgenfunction(fn)


class ShutdownTestItem(pytest.Item):
    """After the tests on one launch: shut it down, then run the parts of its generator tests after `yield`."""

    def __init__(self, *, fixture_name: str, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.fixture_name = fixture_name

    def runtest(self) -> None:
        session = _SESSIONS.get(self.fixture_name)
        if session is None:
            return
        session.shutdown()
        parts, session.after_shutdown = session.after_shutdown, []
        errors = []
        for part in parts:
            try:
                part()
            except BaseException as e:
                errors.append(e)
        if errors:
            raise errors[0]

    def reportinfo(self) -> tuple[Any, int, str]:
        return self.path, 0, self.name


def _add_launch_fixtures(items: list[Any]) -> None:
    for item in items:
        mark = _marker(item)
        if mark is None:
            continue
        name = _marked_fixture(item)
        if name is None:
            item.add_marker(pytest.mark.skip(reason="the launch marker needs fixture=<a launch_pytest fixture>"))
            continue
        if name not in item.fixturenames:
            item.fixturenames.insert(0, name)
        if mark.kwargs.get("shutdown") and (inspect.isgeneratorfunction(item.obj)
                                            or inspect.isasyncgenfunction(item.obj)):
            item.add_marker(pytest.mark.skip(reason="shutdown=True is not allowed with a generator test"))


def _session(request: pytest.FixtureRequest) -> LaunchSession:
    name = _marked_fixture(request.node)
    if name is None:
        raise pytest.UsageError("launch_service/launch_context are for tests marked @pytest.mark.launch(fixture=…)")
    request.getfixturevalue(name)
    return _SESSIONS[name]


@pytest.fixture
def launch_service(request: pytest.FixtureRequest) -> Any:
    return _session(request).service


@pytest.fixture
def launch_context(request: pytest.FixtureRequest) -> Any:
    return _session(request).service.context


@pytest.hookimpl(tryfirst=True)
def pytest_pyfunc_call(pyfuncitem: Any) -> Any:
    mark = _marker(pyfuncitem)
    if mark is None:
        return None
    name = _marked_fixture(pyfuncitem)
    session = _SESSIONS.get(name or "")
    fn = pyfuncitem.obj
    args = {a: pyfuncitem.funcargs[a] for a in pyfuncitem._fixtureinfo.argnames}
    if mark.kwargs.get("shutdown") and session is not None:
        session.shutdown()
    if inspect.iscoroutinefunction(fn):
        asyncio.run(fn(**args))
    elif inspect.isasyncgenfunction(fn):
        _run_async_generator(fn(**args), session, pyfuncitem)
    elif inspect.isgeneratorfunction(fn):
        _run_generator(fn(**args), session, pyfuncitem)
    else:
        fn(**args)
    return True


def _function_scoped(pyfuncitem: Any) -> bool:
    name = _marked_fixture(pyfuncitem)
    defs = pyfuncitem._fixtureinfo.name2fixturedefs.get(name or "")
    return not defs or defs[-1].scope == "function"


def _rest(step: Any, session: LaunchSession | None, pyfuncitem: Any) -> None:
    """The part after the yield: now (function scope) or after the launch has been shut down at teardown."""
    if session is None or _function_scoped(pyfuncitem):
        if session is not None:
            session.shutdown()
        step()
    else:
        session.after_shutdown.append(step)


def _run_generator(gen: Any, session: LaunchSession | None, pyfuncitem: Any) -> None:
    next(gen)

    def finish() -> None:
        try:
            next(gen)
        except StopIteration:
            return
        raise RuntimeError(f"{pyfuncitem.name}: a launch test generator must yield exactly once")

    _rest(finish, session, pyfuncitem)


def _run_async_generator(agen: Any, session: LaunchSession | None, pyfuncitem: Any) -> None:
    loop = asyncio.new_event_loop()
    loop.run_until_complete(agen.__anext__())

    def finish() -> None:
        try:
            loop.run_until_complete(agen.__anext__())
        except StopAsyncIteration:
            return
        finally:
            loop.close()
        raise RuntimeError(f"{pyfuncitem.name}: a launch test generator must yield exactly once")

    _rest(finish, session, pyfuncitem)


# ---- launch_pytest.tools.process ------------------------------------------------------------------------------


def _wait_event(context: Any, action: Any, handler_for: Any, timeout: float | None,
                condition: Any = None) -> bool:
    """Wait for the NEXT event of `action` the handler sees (or until `condition()` holds)."""
    event = threading.Event()
    handler = handler_for(action, event)
    engine = context.engine
    done = threading.Event()
    engine_call = _call_on_launch_thread(context)
    engine_call(lambda: (context.register_event_handler(handler, append=True), done.set()))
    done.wait(5.0)
    try:
        if condition is None:
            return event.wait(timeout)
        import time

        deadline = None if timeout is None else time.monotonic() + timeout
        while not condition():
            left = None if deadline is None else deadline - time.monotonic()
            if left is not None and left <= 0:
                return bool(condition())
            event.wait(left if left is None else min(left, 0.1))
            event.clear()
        return True
    finally:
        engine_call(lambda: _unregister(context, handler))
        del engine


def _unregister(context: Any, handler: Any) -> None:
    try:
        context.unregister_event_handler(handler)
    except ValueError:
        pass


def _call_on_launch_thread(context: Any) -> Any:
    for session in list(_SESSIONS.values()):
        if session.service.context is context:
            return session.service.call
    return lambda f: f()


def _on_start(action: Any, event: threading.Event) -> Any:
    from diffctl.launch_legacy.event_handlers import OnProcessStart

    return OnProcessStart(target_action=action, on_start=lambda e, c: event.set())


def _on_exit(action: Any, event: threading.Event) -> Any:
    from diffctl.launch_legacy.event_handlers import OnProcessExit

    return OnProcessExit(target_action=action, on_exit=lambda e, c: event.set())


def _on_stdout(action: Any, event: threading.Event) -> Any:
    from diffctl.launch_legacy.event_handlers import OnProcessIO

    return OnProcessIO(target_action=action, on_stdout=lambda e: event.set())


def _on_stderr(action: Any, event: threading.Event) -> Any:
    from diffctl.launch_legacy.event_handlers import OnProcessIO

    return OnProcessIO(target_action=action, on_stderr=lambda e: event.set())


def wait_for_start_sync(launch_context: Any, action: Any, timeout: float | None = None) -> bool:
    return _wait_event(launch_context, action, _on_start, timeout)


def wait_for_exit_sync(launch_context: Any, action: Any, timeout: float | None = None) -> bool:
    return _wait_event(launch_context, action, _on_exit, timeout)


def _condition(read: Any, validate: Any, asserting: bool) -> Any:
    def check() -> bool:
        if not asserting:
            return bool(validate(read()))
        try:
            validate(read())
        except AssertionError:
            return False
        return True

    return check


def wait_for_output_sync(launch_context: Any, action: Any, validate_output: Any, timeout: float | None = None) -> bool:
    return _wait_event(launch_context, action, _on_stdout, timeout,
                       _condition(action.get_stdout, validate_output, False))


def assert_output_sync(launch_context: Any, action: Any, validate_output: Any, timeout: float | None = None) -> None:
    if not _wait_event(launch_context, action, _on_stdout, timeout,
                       _condition(action.get_stdout, validate_output, True)):
        validate_output(action.get_stdout())


def wait_for_stderr_sync(launch_context: Any, action: Any, validate_output: Any, timeout: float | None = None) -> bool:
    return _wait_event(launch_context, action, _on_stderr, timeout,
                       _condition(action.get_stderr, validate_output, False))


def assert_stderr_sync(launch_context: Any, action: Any, validate_output: Any, timeout: float | None = None) -> None:
    if not _wait_event(launch_context, action, _on_stderr, timeout,
                       _condition(action.get_stderr, validate_output, True)):
        validate_output(action.get_stderr())


def _async(function: Any) -> Any:
    @functools.wraps(function)
    async def run(*args: Any, **kwargs: Any) -> Any:
        return await asyncio.get_running_loop().run_in_executor(None, functools.partial(function, *args, **kwargs))

    return run


wait_for_start = _async(wait_for_start_sync)
wait_for_exit = _async(wait_for_exit_sync)
wait_for_output = _async(wait_for_output_sync)
assert_output = _async(assert_output_sync)
wait_for_stderr = _async(wait_for_stderr_sync)
assert_stderr = _async(assert_stderr_sync)
