"""rclpy.duration.Duration: signed nanoseconds; no addition of two durations, as in rclpy."""

from __future__ import annotations

from typing import Any

from diffctl.client.interfaces import cls

S_TO_NS = 1_000_000_000
RMW_DURATION_INFINITE = 2**63 - 1
_new = object.__new__


class Duration:
    def __init__(self, *, seconds: int | float = 0, nanoseconds: int = 0) -> None:
        total = int(seconds * S_TO_NS) + int(nanoseconds)
        if total >= 2**63 or total < -(2**63):
            raise OverflowError("Total nanoseconds value is too large to store in C duration.")
        self._nanoseconds = total

    @classmethod
    def from_nanoseconds(cls_, nanoseconds: int) -> Duration:
        """rclcpp's `Duration::from_nanoseconds`: a Duration from an int, without the constructor's seconds
        arithmetic (diffctl's addition, for loops that make one per cycle); the range is still checked."""
        if not -(2**63) <= nanoseconds < 2**63:
            raise OverflowError("Total nanoseconds value is too large to store in C duration.")
        d = _new(cls_)
        d._nanoseconds = nanoseconds
        return d

    @property
    def nanoseconds(self) -> int:
        return self._nanoseconds

    def __repr__(self) -> str:
        return f"Duration(nanoseconds={self._nanoseconds})"

    def __str__(self) -> str:
        if self._nanoseconds == RMW_DURATION_INFINITE:
            return "Infinite"
        return f"{self._nanoseconds} nanoseconds"

    def _cmp(self, other: object, op: Any) -> Any:
        if isinstance(other, Duration):
            return op(self._nanoseconds, other._nanoseconds)
        return NotImplemented

    def __eq__(self, other: object) -> bool:
        return self._cmp(other, lambda a, b: a == b)

    def __ne__(self, other: object) -> bool:
        return self._cmp(other, lambda a, b: a != b)

    def __lt__(self, other: object) -> bool:
        return self._cmp(other, lambda a, b: a < b)

    def __le__(self, other: object) -> bool:
        return self._cmp(other, lambda a, b: a <= b)

    def __gt__(self, other: object) -> bool:
        return self._cmp(other, lambda a, b: a > b)

    def __ge__(self, other: object) -> bool:
        return self._cmp(other, lambda a, b: a >= b)

    __hash__ = None  # type: ignore[assignment]

    def to_msg(self) -> Any:
        sec, nsec = divmod(self._nanoseconds, S_TO_NS)
        return cls("builtin_interfaces/msg/Duration")(sec=sec, nanosec=nsec)

    @classmethod
    def from_msg(cls_, msg: Any) -> Duration:
        if not isinstance(msg, cls("builtin_interfaces/msg/Duration")):
            raise TypeError("Must pass a builtin_interfaces.msg.Duration object")
        return cls_(seconds=msg.sec, nanoseconds=msg.nanosec)

    def get_c_duration(self) -> Duration:
        return self


Infinite = Duration(nanoseconds=RMW_DURATION_INFINITE)
