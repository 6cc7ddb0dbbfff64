"""ReadyToTest: the action a launch test's description reaches when its tests may begin."""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import Any

from diffctl.launch.action import Action

_logger = logging.getLogger(__name__)


class ReadyToTest(Action):
    """Calls whoever waits for it (the test runner, launch_pytest) when it is visited."""

    def __init__(self) -> None:
        super().__init__()
        self._cb_list: list[Callable[[], Any]] = []

    def _add_callback(self, callback: Callable[[], Any]) -> None:
        self._cb_list.append(callback)

    def execute(self, context: Any) -> None:
        for callback in self._cb_list:
            try:
                callback()
            except Exception as e:  # a waiter's failure is not the launch's
                _logger.error(e)
        return None
