"""`@post_shutdown_test()`: a TestCase class whose tests run once the launch has ended."""

from __future__ import annotations

from collections.abc import Callable


def post_shutdown_test() -> Callable[[type], type]:
    def decorator(test_item: type) -> type:
        if not isinstance(test_item, type):
            raise TypeError("postcondition_test should decorate test classes")
        test_item.__post_shutdown_test__ = True  # type: ignore[attr-defined]
        return test_item

    return decorator
