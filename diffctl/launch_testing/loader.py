"""Reading a launch test: its generate_test_description (one TestRun per parametrization) and its TestCase
classes, split into the tests that run while the launch does and the `post_shutdown_test` ones.

Each TestRun gets its own subclasses of the module's TestCase classes, so what one run binds to them
(proc_info, proc_output, the test description's values) does not leak into the next.
"""

from __future__ import annotations

import functools
import inspect
import itertools
import os
import unittest
import warnings
from collections.abc import Callable, Iterator
from typing import Any

from .actions import ReadyToTest


def slim_formatwarning(msg: Any, *args: Any, **kwargs: Any) -> str:
    """Warnings as one 'Warning: …' line, without the source line (launch_test's own warnings)."""
    return "Warning: " + str(msg) + os.linesep


warnings.formatwarning = slim_formatwarning


def _ready_actions(entities: Any) -> Iterator[ReadyToTest]:
    """Every ReadyToTest reachable from `entities`, conditional sub-entities included, depth first."""
    for entity in entities:
        if isinstance(entity, ReadyToTest):
            yield entity
        yield from _ready_actions(entity.describe_sub_entities())
        for _, sub_entities in entity.describe_conditional_sub_entities():
            yield from _ready_actions(sub_entities)


def _normalize_ld(launch_description_fn: Callable[..., Any]) -> Callable[..., tuple[Any, dict[str, Any]]]:
    """generate_test_description as (description, test values) with `ready_fn` plumbed into its ReadyToTest."""

    def normalized(**kwargs: Any) -> tuple[Any, dict[str, Any]]:
        ready_fn = kwargs.pop("ready_fn")
        result = launch_description_fn(**kwargs)
        description, values = result if isinstance(result, tuple) else (result, {})
        ready = next(_ready_actions(description.entities), None)
        if ready is None:
            raise Exception(
                "generate_test_description functions must return a LaunchDescription containing a ReadyToTest "
                "action"
            )
        ready._add_callback(ready_fn)
        return description, values

    return normalized


class TestRun:
    """One launch of a test file (one per parametrization) and the tests to run with it."""

    def __init__(self, name: str, test_description_function: Callable[..., Any], param_args: dict[str, Any],
                 pre_shutdown_tests: Any, post_shutdown_tests: Any) -> None:
        self.name = name
        if not hasattr(test_description_function, "__markers__"):
            test_description_function.__markers__ = {}  # type: ignore[attr-defined]
        self._test_description_function = test_description_function
        self.normalized_test_description = _normalize_ld(test_description_function)
        self.param_args = param_args
        self.pre_shutdown_tests = pre_shutdown_tests
        self.post_shutdown_tests = post_shutdown_tests
        self.timeout = getattr(test_description_function, "__ready_to_test_action_timeout__", 15)
        if self.param_args:  # 'test_x[a, b]': which run a result came from shows in its name
            for case in self.all_cases():
                method = getattr(case, case._testMethodName)
                case._testMethodName += self._format_params()
                setattr(case, case._testMethodName, method)
        for suite in itertools.chain(_suites(pre_shutdown_tests), _suites(post_shutdown_tests)):
            suite._removeTestAtIndex = lambda *args, **kwargs: None  # results refer to the cases afterwards

    @property
    def markers(self) -> dict[str, Any]:
        return self._test_description_function.__markers__  # type: ignore[attr-defined]

    def bind(self, tests: Any, injected_attributes: dict[str, Any] | None = None,
             injected_args: dict[str, Any] | None = None) -> None:
        """Give `tests` the objects they may use: as attributes (`self.proc_info`, deprecated, with a warning
        on use) and as the arguments of test methods, setUp/tearDown and setUpClass/tearDownClass that name
        them."""
        for name, value in (injected_attributes or {}).items():
            _give_attribute_to_tests(value, name, tests)
        _bind_test_args_to_tests(injected_args or {}, tests)

    def get_launch_description(self) -> Any:
        """The launch description alone, to look at (`--show-args`), never to launch."""
        return self.normalized_test_description(ready_fn=lambda: None)[0]

    def all_cases(self) -> Iterator[unittest.TestCase]:
        yield from _cases(self.pre_shutdown_tests)
        yield from _cases(self.post_shutdown_tests)

    def __str__(self) -> str:
        return self.name + self._format_params()

    def _format_params(self) -> str:
        return "[" + ", ".join(map(str, self.param_args.values())) + "]" if self.param_args else ""


def LoadTestsFromPythonModule(module: Any, *, name: str = "launch_tests") -> list[TestRun]:
    """The TestRuns of a module defining generate_test_description (parametrized: one per value)."""
    generate = module.generate_test_description
    runs = generate() if hasattr(generate, "__parametrized__") else [(generate, {})]
    return [
        TestRun(name, description, args, PreShutdownTestLoader().loadTestsFromModule(module),
                PostShutdownTestLoader().loadTestsFromModule(module))
        for description, args in runs
    ]


class _SelectingLoader(unittest.TestLoader):
    """unittest's loader keeping only the TestCase classes of one side of the shutdown, each subclassed
    afresh so every run has classes of its own."""

    def __init__(self, post_shutdown: bool) -> None:
        super().__init__()
        self._post_shutdown = post_shutdown

    def loadTestsFromTestCase(self, testCaseClass: type) -> unittest.TestSuite:
        if getattr(testCaseClass, "__post_shutdown_test__", False) != self._post_shutdown:
            return self.suiteClass()
        own = type(testCaseClass.__name__, (testCaseClass,), {"__module__": testCaseClass.__module__})
        return super().loadTestsFromTestCase(own)


def PreShutdownTestLoader() -> unittest.TestLoader:
    return _SelectingLoader(post_shutdown=False)


def PostShutdownTestLoader() -> unittest.TestLoader:
    return _SelectingLoader(post_shutdown=True)


def _with_matching_args(function: Callable[..., Any], candidates: dict[str, Any]) -> Callable[..., Any]:
    accepted = inspect.signature(function).parameters
    return functools.partial(function, **{k: v for k, v in candidates.items() if k in accepted})


def _bind_test_args_to_tests(candidates: dict[str, Any], tests: Any) -> None:
    for case in _cases(tests):
        setattr(case, case._testMethodName, _with_matching_args(getattr(case, case._testMethodName), candidates))
        case.setUp = _with_matching_args(case.setUp, candidates)
        case.tearDown = _with_matching_args(case.tearDown, candidates)
    for cls in _classes(tests):
        cls.setUpClass = _with_matching_args(cls.setUpClass, candidates)
        cls.tearDownClass = _with_matching_args(cls.tearDownClass, candidates)


def _give_attribute_to_tests(value: Any, name: str, tests: Any) -> None:
    def getter(self: Any) -> Any:
        if not getattr(self, "_warned_about_" + name, False):
            warnings.warn(
                f"Automatically adding attributes like self.{name} to the test class will be deprecated in a "
                f"future release.  Instead, add {name} to the test method argument list to access the test "
                "object you need",
                stacklevel=2,
            )
            setattr(self, "_warned_about_" + name, True)
        return value

    for cls in _classes(tests):
        setattr(cls, name, property(fget=getter))


def _cases(tests: Any) -> Iterator[Any]:
    """The test cases of a suite (of suites …), or the one test given."""
    try:
        children = iter(tests)
    except TypeError:
        yield tests
        return
    for child in children:
        yield from _cases(child)


def _suites(tests: Any) -> Iterator[unittest.TestSuite]:
    if isinstance(tests, unittest.TestSuite):
        yield tests
    try:
        children = iter(tests)
    except TypeError:
        return
    for child in children:
        yield from _suites(child)


def _classes(tests: Any) -> Iterator[type]:
    seen: list[type] = []
    for case in _cases(tests):
        if type(case) not in seen:
            seen.append(type(case))
            yield type(case)


__all__ = ["LoadTestsFromPythonModule", "PostShutdownTestLoader", "PreShutdownTestLoader", "TestRun",
           "slim_formatwarning"]
