"""GTest: a gtest binary run as a Test action."""

from __future__ import annotations

from typing import Any

from .test import Test


class GTest(Test):
    """Runs the test program at `path` (a path or substitutions); `timeout` and the rest as Test's."""

    def __init__(self, *, path: Any, **kwargs: Any) -> None:
        super().__init__(cmd=[path], **kwargs)
        self.__path = path

    @property
    def path(self) -> Any:
        return self.__path
