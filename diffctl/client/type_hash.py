"""rclpy.type_hash.TypeHash: a type's RIHS hash (version and 32 bytes), printed as RIHS01_<hex>."""

from __future__ import annotations

_TYPE_HASH_SIZE = 32


class TypeHash:
    __slots__ = ["_value", "_version"]  # ros2cli relies on the slots, as on rclpy's
    _TYPE_HASH_SIZE = _TYPE_HASH_SIZE

    def __init__(self, version: int = -1, value: bytes = bytes(_TYPE_HASH_SIZE)) -> None:
        self.version = version
        self.value = value

    @property
    def version(self) -> int:
        return self._version

    @version.setter
    def version(self, value: int) -> None:
        assert isinstance(value, int)
        self._version = value

    @property
    def value(self) -> bytes:
        return self._value

    @value.setter
    def value(self, value: bytes) -> None:
        assert isinstance(value, bytes)
        self._value = value

    @classmethod
    def from_string(cls, text: str) -> TypeHash:
        """From the `RIHS01_<64 hex>` form the bus and `diffctl.interfaces.type_hash` use."""
        head, _, digits = text.partition("_")
        return cls(int(head[4:]), bytes.fromhex(digits))

    def __eq__(self, other: object) -> bool:
        return isinstance(other, TypeHash) and (self._version, self._value) == (other._version, other._value)

    __hash__ = None  # type: ignore[assignment]  (mutable, as rclpy's)

    def __str__(self) -> str:
        if self._version <= 0 or len(self._value) != _TYPE_HASH_SIZE:
            return "INVALID"
        return f"RIHS{self._version:02}_{self._value.hex()}"

    def __repr__(self) -> str:
        return f"TypeHash(version={self._version}, value={self._value!r})"
