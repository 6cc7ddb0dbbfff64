"""Test: a process run as a test by a launch (a gtest binary, a pytest run), stopped at its timeout."""

from __future__ import annotations

from typing import Any

from diffctl.launch.actions import EmitEvent, ExecuteProcess, TimerAction
from diffctl.launch.event_handlers import OnProcessExit
from diffctl.launch.events import matches_action
from diffctl.launch.events.process import ShutdownProcess


class Test(ExecuteProcess):
    """An ExecuteProcess that is interrupted (SIGINT, then launch's escalation) when it is still running
    `timeout` seconds after it started; every other argument is ExecuteProcess's."""

    def __init__(self, *, timeout: Any = None, kill_timeout: Any = 5.0, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__timeout = timeout
        self.__timer: TimerAction | None = None

    @property
    def timeout(self) -> Any:
        return self.__timeout

    def __cancel_timer(self, event: Any, context: Any) -> None:
        if self.__timer is not None:
            self.__timer.cancel()

    def execute(self, context: Any) -> list[Any] | None:
        entities = super().execute(context)
        if not self.__timeout:
            return entities
        self.__timer = TimerAction(
            period=self.__timeout,
            actions=[EmitEvent(event=ShutdownProcess(process_matcher=matches_action(self)))],
        )
        context.register_event_handler(OnProcessExit(target_action=self, on_exit=self.__cancel_timer))
        return [*(entities or []), self.__timer]
