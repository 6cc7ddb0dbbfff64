"""rclpy.time.Time: a point on one clock type; SYSTEM_TIME unless told, as in rclpy."""

from __future__ import annotations

from typing import Any

from diffctl.client.clock_type import ClockType
from diffctl.client.duration import S_TO_NS, Duration
from diffctl.client.interfaces import cls

_new = object.__new__


class Time:
    def __init__(self, *, seconds: int | float = 0, nanoseconds: int = 0,
                 clock_type: ClockType = ClockType.SYSTEM_TIME) -> None:
        if not isinstance(clock_type, ClockType):
            raise TypeError("Clock type must be a ClockType enum")
        if seconds < 0:
            raise ValueError("Seconds value must not be negative")
        if nanoseconds < 0:
            raise ValueError("Nanoseconds value must not be negative")
        total = int(seconds * S_TO_NS) + int(nanoseconds)
        if total >= 2**63:
            raise OverflowError("Total nanoseconds value is too large to store in C time point.")
        self._nanoseconds = total
        self._clock_type = clock_type

    @classmethod
    def from_nanoseconds(cls_, nanoseconds: int, clock_type: ClockType = ClockType.SYSTEM_TIME) -> Time:
        """A Time from an int of nanoseconds, without the constructor's seconds arithmetic and type checks
        (diffctl's addition, for loops that make one per cycle); the range is still checked."""
        if not 0 <= nanoseconds < 2**63:
            if nanoseconds < 0:
                raise ValueError("Nanoseconds value must not be negative")
            raise OverflowError("Total nanoseconds value is too large to store in C time point.")
        t = _new(cls_)
        t._nanoseconds = nanoseconds
        t._clock_type = clock_type
        return t

    @property
    def nanoseconds(self) -> int:
        return self._nanoseconds

    @property
    def clock_type(self) -> ClockType:
        return self._clock_type

    def seconds_nanoseconds(self) -> tuple[int, int]:
        return divmod(self._nanoseconds, S_TO_NS)

    def __repr__(self) -> str:
        return f"Time(nanoseconds={self._nanoseconds}, clock_type={self._clock_type.name})"

    def __add__(self, other: Any) -> Time:
        if isinstance(other, Duration):
            try:
                return Time(nanoseconds=self._nanoseconds + other.nanoseconds, clock_type=self._clock_type)
            except OverflowError as e:
                raise OverflowError("Addition leads to overflow in C storage.") from e
        return NotImplemented

    __radd__ = __add__

    def __sub__(self, other: Any) -> Any:
        if isinstance(other, Time):
            if self._clock_type != other._clock_type:
                raise TypeError("Can't subtract times with different clock types")
            return Duration(nanoseconds=self._nanoseconds - other._nanoseconds)
        if isinstance(other, Duration):
            try:
                return Time(nanoseconds=self._nanoseconds - other.nanoseconds, clock_type=self._clock_type)
            except ValueError as e:
                raise ValueError("Subtraction leads to negative time.") from e
        return NotImplemented

    def _cmp(self, other: object, op: Any) -> Any:
        if isinstance(other, Time):
            if self._clock_type != other._clock_type:
                raise TypeError("Can't compare times with different clock types")
            return op(self._nanoseconds, other._nanoseconds)
        return NotImplemented

    def __eq__(self, other: object) -> bool:
        return self._cmp(other, lambda a, b: a == b)

    def __ne__(self, other: object) -> bool:
        if isinstance(other, Time):
            return not self.__eq__(other)
        return NotImplemented

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
        sec, nsec = self.seconds_nanoseconds()
        return cls("builtin_interfaces/msg/Time")(sec=sec, nanosec=nsec)

    @classmethod
    def from_msg(cls_, msg: Any, clock_type: ClockType = ClockType.ROS_TIME) -> Time:
        if not isinstance(msg, cls("builtin_interfaces/msg/Time")):
            raise TypeError("Must pass a builtin_interfaces.msg.Time object")
        return cls_(seconds=msg.sec, nanoseconds=msg.nanosec, clock_type=clock_type)
