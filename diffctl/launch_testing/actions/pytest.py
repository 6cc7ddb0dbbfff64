"""PyTest: a pytest run of one file, as a Test action."""

from __future__ import annotations

import sys
from typing import Any

from .test import Test


class PyTest(Test):
    """Runs `python -m pytest path` with this interpreter; `timeout` and the rest as Test's."""

    def __init__(self, *, path: Any, **kwargs: Any) -> None:
        super().__init__(cmd=[sys.executable, "-m", "pytest", path], **kwargs)
        self.__path = path

    @property
    def path(self) -> Any:
        return self.__path
