"""launch_pytest's pytest plugin: launch fixtures are launched on the test's asyncio loop, and tests marked
`@pytest.mark.launch(fixture=…)` run while that loop drives the launch.

Between tests the loop does not run, so a test sees its processes' events from where the previous one (or
the fixture's ReadyToTest) left off. A generator test on a launch of wider scope than a function becomes two
items: the part before `yield` with the other tests, the rest (`…[shutdown_test]`) after them, once the
launch is shut down.
"""

from __future__ import annotations

import asyncio
import functools
import inspect
from collections.abc import Callable, Iterable, Iterator, Sequence
from typing import Any

import pytest
from _pytest.outcomes import fail, skip

from .fixture import (
    finalize_launch_service,
    get_event_loop_fixture,
    get_launch_context_fixture,
    get_launch_service_fixture,
)


class LaunchTestWarning(pytest.PytestWarning):
    """A launch test this plugin cannot run as written."""


def pytest_configure(config: Any) -> None:
    config.addinivalue_line(
        "markers", "launch: mark the test as a launch test, it will be run using the specified launch_pad."
    )


def iterate_ready_to_test_actions(entities: Iterable[Any]) -> Iterator[Any]:
    """Every ReadyToTest reachable from `entities`, conditional sub-entities included."""
    from .actions import ReadyToTest

    for entity in entities:
        if isinstance(entity, ReadyToTest):
            yield entity
        yield from iterate_ready_to_test_actions(entity.describe_sub_entities())
        for _, sub_entities in entity.describe_conditional_sub_entities():
            yield from iterate_ready_to_test_actions(sub_entities)


def get_ready_to_test_action(launch_description: Any) -> Any:
    """The one ReadyToTest of the description; without one, one is appended (tests start once everything
    before it was visited)."""
    found = list(iterate_ready_to_test_actions(launch_description.entities))
    if len(found) > 1:
        raise RuntimeError(
            "launch_pytest fixtures must return a LaunchDescription containing only one ReadyToTest action"
        )
    if found:
        return found[0]
    from .actions import ReadyToTest

    ready = ReadyToTest()
    launch_description.entities.append(ready)
    return ready


async def _ready_or_ended(ready: asyncio.Event, launch: asyncio.Future) -> None:
    """Until the ReadyToTest is visited; a launch that ends first is an error, not a hang."""
    waiter = asyncio.ensure_future(ready.wait())
    await asyncio.wait({waiter, launch}, return_when=asyncio.FIRST_COMPLETED)
    if waiter.done():
        return
    waiter.cancel()
    rc = launch.result() if not launch.cancelled() and launch.exception() is None else None
    raise RuntimeError(f"the launch ended (return code {rc}) before its ReadyToTest action was visited")


@pytest.hookimpl(hookwrapper=True, tryfirst=True)
def pytest_fixture_setup(fixturedef: Any, request: Any) -> Any:
    """A launch fixture's value is the description it returns, launched: the fixture is set up once its
    ReadyToTest has been visited, and finalized by shutting the launch down."""
    if not getattr(fixturedef.func, "_launch_pytest_fixture", False):
        yield
        return
    launch_service, event_loop = (request.getfixturevalue(name) for name in ("launch_service", "event_loop"))
    eprefix = f"When running launch_pytest fixture '{fixturedef.func.__name__}':"
    description = _description_in((yield).get_result(), eprefix)
    options = fixturedef.func._launch_pytest_fixture_options
    launch_service.include_launch_description(description)
    task = event_loop.create_task(launch_service.run_async(shutdown_when_idle=options["shutdown_when_idle"]))
    ready = get_ready_to_test_action(description)
    asyncio.set_event_loop(event_loop)
    ready_event = asyncio.Event()
    ready._add_callback(ready_event.set)
    fixturedef.addfinalizer(functools.partial(finalize_launch_service, launch_service, eprefix=eprefix,
                                              auto_shutdown=options["auto_shutdown"]))
    run_until_complete(event_loop, _ready_or_ended(ready_event, task))


def _description_in(value: Any, eprefix: str) -> Any:
    """The LaunchDescription a launch fixture returned, alone or first of a sequence."""
    from diffctl.launch import LaunchDescription

    first = value[0] if isinstance(value, Sequence) and not isinstance(value, str) and len(value) else value
    if not isinstance(first, LaunchDescription):
        raise AssertionError(
            f"{eprefix} return value must be either a launch description or a sequence which first item is a "
            "launch description"
        )
    return first


def is_launch_test(item: Any) -> bool:
    return item.get_closest_marker("launch") is not None


def is_launch_test_mark_valid(item: Any) -> bool:
    kwargs = item.get_closest_marker("launch").kwargs
    return kwargs.get("fixture") is not None


def has_shutdown_kwarg(item: Any) -> bool:
    return bool(item.get_closest_marker("launch").kwargs.get("shutdown", False))


def get_launch_test_fixture(item: Any) -> Any:
    mark = item.get_closest_marker("launch")
    return None if mark is None else mark.kwargs.get("fixture")


def _fixture_name(fixture: Any) -> str:
    marker = getattr(fixture, "_pytestfixturefunction", None) or getattr(fixture, "_fixture_function_marker", None)
    return getattr(marker, "name", None) or fixture.__name__


def _fixture_scope(fixture: Any) -> str:
    marker = getattr(fixture, "_pytestfixturefunction", None) or getattr(fixture, "_fixture_function_marker", None)
    scope = getattr(marker, "scope", "function")
    return scope if isinstance(scope, str) else "function"


def get_launch_test_fixturename(item: Any) -> str | None:
    fixture = get_launch_test_fixture(item)
    return None if fixture is None else _fixture_name(fixture)


def is_valid_test_item(obj: Any) -> bool:
    return (inspect.iscoroutinefunction(obj) or inspect.isfunction(obj) or inspect.isgeneratorfunction(obj)
            or inspect.isasyncgenfunction(obj))


def need_shutdown_test_item(obj: Any) -> bool:
    """Generator tests have a part that runs after shutdown."""
    return inspect.isgeneratorfunction(obj) or inspect.isasyncgenfunction(obj)


def _not_paired(**kwargs: Any) -> None:
    skip("shutdown test skipped because the test it finishes did not run")


_not_paired._launch_pytest_wrapped = True  # type: ignore[attr-defined]


def _shutdown_twin(item: Any) -> Any:
    """The item running the after-`yield` part of generator test `item` (same marks and parameters, an id
    of its own); until that test runs and hands it the rest of its generator, it would only skip."""
    twin = pytest.Function.from_parent(
        item.parent, name=f"{item.name}[shutdown_test]", callspec=getattr(item, "callspec", None),
        callobj=item.obj, fixtureinfo=item._fixtureinfo,
        # pytest 8.4+ makes the id of a parametrized item from originalname and the parameters
        originalname=f"{item.originalname}[shutdown_test]",
    )
    twin.obj = _not_paired
    return twin


def generate_test_items(collector: Any, name: str, obj: Any, fixturename: str, *, is_shutdown: bool,
                        needs_renaming: bool) -> list[Any]:
    """The items of test function `obj` using launch fixture `fixturename` (several when it is
    parametrized), with that fixture, launch_service and event_loop requested."""
    # usefixtures, not fixturenames: a parametrized launch fixture must multiply the items
    pytest.mark.usefixtures(fixturename, "launch_service", "event_loop")(obj)
    items = list(collector._genfunctions(name, obj))
    if needs_renaming:
        items = [_shutdown_twin(item) for item in items]
    for item in items:
        item._launch_pytest_is_shutdown = is_shutdown
    return items


def from_parent(cls: Any, *args: Any, **kwargs: Any) -> Any:
    return cls.from_parent(*args, **kwargs)


@pytest.hookimpl(tryfirst=True)
def pytest_pycollect_makeitem(collector: Any, name: str, obj: Any) -> Any:
    """Collect launch tests: coroutines and generators too, each with the fixtures it runs with."""
    if not (collector.funcnamefilter(name) and is_valid_test_item(obj)):
        return None
    probe = pytest.Function.from_parent(collector, name=name)  # to see the marks of module and class too
    if not is_launch_test(probe):
        return None
    if not is_launch_test_mark_valid(probe):
        message = '"fixture" keyword argument is required in a pytest.mark.launch() decorator'
        probe.warn(LaunchTestWarning(message))
        probe.add_marker(pytest.mark.skip(message))
        return [probe]
    fixture = get_launch_test_fixture(probe)
    fixturename = _fixture_name(fixture)
    items = generate_test_items(collector, name, obj, fixturename, is_shutdown=has_shutdown_kwarg(probe),
                                needs_renaming=False)
    if need_shutdown_test_item(obj) and _fixture_scope(fixture) != "function":
        # with a function-scoped launch, one item runs both parts (a second would get a second launch)
        twins = generate_test_items(collector, name, obj, fixturename, is_shutdown=True, needs_renaming=True)
        for item, twin in zip(items, twins, strict=True):
            item._launch_pytest_shutdown_item = twin
        items += twins
    return items


def is_shutdown_test(item: Any) -> bool:
    return getattr(item, "_launch_pytest_is_shutdown", False)


def is_same_launch_test_fixture(left_item: Any, right_item: Any) -> bool:
    """Both items run on one launch: the same fixture of a scope wider than a function, same parameters."""
    left, right = get_launch_test_fixture(left_item), get_launch_test_fixture(right_item)
    if left is None or right is None or left is not right or _fixture_scope(left) == "function":
        return False
    name = _fixture_name(left)

    def params(item: Any) -> Any:
        callspec = getattr(item, "callspec", None)
        return None if callspec is None else callspec.params.get(name)

    return params(left_item) == params(right_item)


@pytest.hookimpl(trylast=True)
def pytest_collection_modifyitems(session: Any, config: Any, items: list[Any]) -> None:
    """Each shutdown test moves after the last other test on its launch (keeping the shutdown tests' order)."""
    for index in range(len(items) - 1, -1, -1):
        item = items[index]
        if not is_launch_test(item) or not is_shutdown_test(item):
            continue
        target = None
        for later in range(index + 1, len(items)):
            other = items[later]
            if is_same_launch_test_fixture(item, other) and not is_shutdown_test(other):
                target = later
        if target is not None:
            items.insert(target, items.pop(index))


@pytest.hookimpl(hookwrapper=True, tryfirst=True)
def pytest_pyfunc_call(pyfuncitem: Any) -> Any:
    """Replace the test function by one that runs it on the launch's loop (shutting the launch down first for
    `shutdown=True` tests and for what follows a generator's yield)."""
    if not is_launch_test(pyfuncitem):
        yield
        return
    func = pyfuncitem.obj
    if has_shutdown_kwarg(pyfuncitem) and need_shutdown_test_item(func):
        fail("generator or async generator based launch test items cannot be marked with shutdown=True")
    fixture = get_launch_test_fixture(pyfuncitem)
    scope = _fixture_scope(fixture)
    event_loop = pyfuncitem.funcargs["event_loop"]
    launch_service = pyfuncitem.funcargs["launch_service"]
    auto_shutdown = getattr(fixture, "_launch_pytest_fixture_options", {}).get("auto_shutdown", True)
    on_shutdown = functools.partial(finalize_launch_service, launch_service,
                                    eprefix=f"When running test {func.__name__}", auto_shutdown=auto_shutdown)
    before_test = on_shutdown if is_shutdown_test(pyfuncitem) else None
    twin = getattr(pyfuncitem, "_launch_pytest_shutdown_item", None)
    if inspect.iscoroutinefunction(func):
        pyfuncitem.obj = wrap_coroutine(func, event_loop, before_test)
    elif inspect.isgeneratorfunction(func):
        if scope != "function" and twin is not None:
            pyfuncitem.obj, twin.obj = wrap_generator(func, event_loop, on_shutdown)
        else:
            pyfuncitem.obj = wrap_generator_fscope(func, event_loop, on_shutdown)
    elif inspect.isasyncgenfunction(func):
        if scope != "function" and twin is not None:
            pyfuncitem.obj, twin.obj = wrap_asyncgen(func, event_loop, on_shutdown)
        else:
            pyfuncitem.obj = wrap_asyncgen_fscope(func, event_loop, on_shutdown)
    elif not getattr(func, "_launch_pytest_wrapped", False):
        pyfuncitem.obj = wrap_func(func, event_loop, before_test)
    yield


def run_until_complete(loop: asyncio.AbstractEventLoop, future_like: Any) -> Any:
    """loop.run_until_complete, retrieving the future's exception if it fails (no 'never retrieved' noise)."""
    future = asyncio.ensure_future(future_like, loop=loop)
    try:
        return loop.run_until_complete(future)
    except BaseException:
        if future.done() and not future.cancelled():
            future.exception()
        raise


def wrap_coroutine(func: Callable[..., Any], event_loop: Any, before_test: Callable[[], Any] | None) -> Any:
    """An async test run as a task of the launch's loop."""

    @functools.wraps(func)
    def inner(**kwargs: Any) -> None:
        if before_test is not None:
            before_test()
        run_until_complete(event_loop, func(**kwargs))

    return inner


def wrap_func(func: Callable[..., Any], event_loop: Any, before_test: Callable[[], Any] | None) -> Any:
    """A plain test run on a worker thread while the launch's loop runs."""

    @functools.wraps(func)
    def inner(**kwargs: Any) -> None:
        if before_test is not None:
            before_test()
        run_until_complete(event_loop, event_loop.run_in_executor(None, functools.partial(func, **kwargs)))

    return inner


def _one_yield_only(kind: str) -> None:
    fail(f"launch tests using {kind} must stop iteration after yielding once", pytrace=False)


def wrap_generator(func: Callable[..., Any], event_loop: Any, on_shutdown: Callable[[], Any]) -> tuple[Any, Any]:
    """The two items of a generator test on a wider-scoped launch: up to the yield, and after shutdown."""
    started: list[Any] = []

    def shutdown(**kwargs: Any) -> None:
        if not started:
            skip("shutdown test skipped because the test failed before")
        on_shutdown()
        try:
            next(started[0])
        except StopIteration:
            return
        _one_yield_only("a generator function")

    shutdown._launch_pytest_wrapped = True  # type: ignore[attr-defined]
    shutdown.__name__ = f"{func.__name__}[shutdown]"

    @functools.wraps(func)
    def inner(**kwargs: Any) -> None:
        gen = func(**kwargs)
        run_until_complete(event_loop, event_loop.run_in_executor(None, next, gen))
        started.append(gen)

    return inner, shutdown


def wrap_generator_fscope(func: Callable[..., Any], event_loop: Any, on_shutdown: Callable[[], Any]) -> Any:
    """A generator test on a function-scoped launch: up to the yield, shutdown, the rest."""

    @functools.wraps(func)
    def inner(**kwargs: Any) -> None:
        gen = func(**kwargs)
        run_until_complete(event_loop, event_loop.run_in_executor(None, next, gen))
        on_shutdown()
        try:
            next(gen)
        except StopIteration:
            return
        _one_yield_only("a generator function")

    return inner


def wrap_asyncgen(func: Callable[..., Any], event_loop: Any, on_shutdown: Callable[[], Any]) -> tuple[Any, Any]:
    """As wrap_generator, for an async generator test."""
    started: list[Any] = []

    def shutdown(**kwargs: Any) -> None:
        if not started:
            skip("shutdown test skipped because the test failed before")
        on_shutdown()
        try:
            run_until_complete(event_loop, started[0].__anext__())
        except StopAsyncIteration:
            return
        _one_yield_only("an async gen function")

    shutdown._launch_pytest_wrapped = True  # type: ignore[attr-defined]
    shutdown.__name__ = f"{func.__name__}[shutdown]"

    @functools.wraps(func)
    def inner(**kwargs: Any) -> None:
        agen = func(**kwargs)
        run_until_complete(event_loop, agen.__anext__())
        started.append(agen)

    return inner, shutdown


def wrap_asyncgen_fscope(func: Callable[..., Any], event_loop: Any, on_shutdown: Callable[[], Any]) -> Any:
    """As wrap_generator_fscope, for an async generator test."""

    @functools.wraps(func)
    def inner(**kwargs: Any) -> None:
        agen = func(**kwargs)
        run_until_complete(event_loop, agen.__anext__())
        on_shutdown()
        try:
            run_until_complete(event_loop, agen.__anext__())
        except StopAsyncIteration:
            return
        _one_yield_only("an async gen function")

    return inner


launch_service = get_launch_service_fixture(overridable=False)
launch_context = get_launch_context_fixture(overridable=False)
event_loop = get_event_loop_fixture(overridable=False)
