"""launch_testing.legacy: the old LaunchTestService, where tests are processes and output checks added to a
launch description, and the launch's return code is the verdict (deprecated upstream, kept for old tests)."""

from __future__ import annotations

from typing import Any

from diffctl.launch.actions import EmitEvent, ExecuteProcess, RegisterEventHandler
from diffctl.launch.event_handlers import OnExecutionComplete, OnProcessExit, OnProcessIO, OnShutdown
from diffctl.launch.events import Shutdown

from . import output

_ARMED = "armed"


class LaunchTestService:
    """Tracks the tests added to a launch description: the launch shuts down when every test has finished,
    or at the first failure; `run` turns the outcome into a return code."""

    def __init__(self) -> None:
        self.__tests: dict[str, str] = {}
        self.__processes_rc: dict[str, int] = {}

    def _arm(self, test_name: str) -> None:
        assert test_name not in self.__tests
        self.__tests[test_name] = _ARMED

    def _all_done(self) -> bool:
        return all(state != _ARMED for state in self.__tests.values())

    def _finish(self, test_name: str) -> list[Any] | None:
        assert test_name in self.__tests
        self.__tests[test_name] = "finished"
        return [EmitEvent(event=Shutdown(reason="all tests finished"))] if self._all_done() else None

    def _drop(self, test_name: str) -> None:
        assert test_name in self.__tests
        self.__tests[test_name] = "dropped"

    def _fail(self, test_name: str, reason: str) -> list[Any]:
        assert test_name in self.__tests
        self.__tests[test_name] = "failed"
        for name, state in self.__tests.items():
            if state == _ARMED:
                self.__tests[name] = "dropped"
        return [EmitEvent(event=Shutdown(reason=reason))]

    def _succeed(self, test_name: str, side_effect: str | None = None) -> list[Any]:
        assert test_name in self.__tests
        self.__tests[test_name] = "succeeded"
        if self._all_done():
            return [EmitEvent(event=Shutdown(reason="all tests finished"))]
        if side_effect == "shutdown":
            return [EmitEvent(event=Shutdown(reason="shutdown after test"))]
        return []

    def add_fixture_action(self, launch_description: Any, action: Any, exit_allowed: Any = (0,)) -> Any:
        """Add an action the tests need: a process of it exiting (with a code not in `exit_allowed`, or at
        all when `exit_allowed` is False) shuts the launch down and fails the run."""
        launch_description.add_action(action)
        if not isinstance(action, ExecuteProcess):
            return action

        def on_exit(event: Any, context: Any) -> Any:
            name = event.action.process_details["name"]
            allowed = event.returncode in exit_allowed if isinstance(exit_allowed, (list, tuple)) else exit_allowed
            if context.is_shutdown or allowed:
                return None
            self.__processes_rc[name] = event.returncode or 1
            return EmitEvent(event=Shutdown(reason=f"{name} fixture process died!"))

        launch_description.add_action(RegisterEventHandler(OnProcessExit(target_action=action, on_exit=on_exit)))
        return action

    def add_test_action(self, launch_description: Any, action: Any) -> Any:
        """Add an action that is a test: a process passes by exiting with 0, another action by completing."""
        test_name = f"test_{id(action)}"
        if isinstance(action, ExecuteProcess):
            def on_exit(event: Any, context: Any) -> Any:
                if event.returncode == 0:
                    return self._succeed(test_name)
                name = event.action.process_details["name"]
                self.__processes_rc[name] = event.returncode
                return self._fail(test_name, reason=f"{name} test failed!")

            launch_description.add_action(
                RegisterEventHandler(OnProcessExit(target_action=action, on_exit=on_exit)))
        else:
            def on_completion(event: Any, context: Any) -> Any:
                future = event.action.get_asyncio_future()
                if future is not None:
                    if future.cancelled():
                        return self._drop(test_name)
                    if future.exception() is not None:
                        return self._fail(test_name, str(future.exception()))
                return self._succeed(test_name)

            launch_description.add_action(
                RegisterEventHandler(OnExecutionComplete(target_action=action, on_completion=on_completion)))
        launch_description.add_action(action)
        self._arm(test_name)
        return action

    def add_output_test(self, launch_description: Any, action: Any, output_test: Any, test_suffix: str = "output",
                        output_filter: Any = None, side_effect: str | None = None) -> Any:
        """Check what the process of `action` prints against `output_test` (legacy.output's create_*): it
        passes once every expectation matched, fails if the process ends or the launch shuts down before."""
        assert isinstance(action, ExecuteProcess)
        test_name = f"test_{id(action)}_{test_suffix}"
        collected, collate, matched, expected = output_test
        keep = output_filter or (lambda text: text)
        assert any(expected)
        state = {"out": collected, "left": list(expected)}

        def on_exit(event: Any, context: Any) -> Any:
            # finished here, judged at shutdown: the exit may be seen before the last output is
            return self._finish(test_name) if any(state["left"]) else None

        def on_shutdown(event: Any, context: Any) -> None:
            if any(state["left"]):
                self._fail(test_name, f"not all {action.process_details['name']} output matched!")
            self._succeed(test_name, side_effect)

        def on_stdout(event: Any) -> Any:
            state["out"] = collate(state["out"], keep(event.text))
            state["left"] = [e for e in state["left"] if not matched(state["out"], e)]
            return None if any(state["left"]) else self._succeed(test_name, side_effect)

        launch_description.add_action(RegisterEventHandler(OnProcessExit(target_action=action, on_exit=on_exit)))
        launch_description.add_action(RegisterEventHandler(OnShutdown(on_shutdown=on_shutdown)))
        launch_description.add_action(RegisterEventHandler(OnProcessIO(target_action=action, on_stdout=on_stdout)))
        self._arm(test_name)
        return action

    def run(self, launch_service: Any, *args: Any, **kwargs: Any) -> int:
        """launch_service.run(); a clean launch whose tests failed gives the first failed process's code, or 1."""
        rc = launch_service.run(*args, **kwargs)
        if rc != 0:
            return rc
        failed = next((code for code in self.__processes_rc.values() if code != 0), None)
        if failed is not None:
            return failed
        return 1 if "failed" in self.__tests.values() else 0


__all__ = ["LaunchTestService", "output"]
