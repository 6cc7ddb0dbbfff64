"""The type objects of rosidl_parser.definition that generated message classes expose as `SLOT_TYPES`.

Only the types (basic, named, strings, arrays, sequences) and the name constants users' code and
rosidl_runtime_py test against: class names, attributes and equality behave as rosidl_parser's (Jazzy).
"""

from __future__ import annotations

from collections.abc import Iterable

SIGNED_NONEXPLICIT_INTEGER_TYPES = ("short", "long", "long long")
UNSIGNED_NONEXPLICIT_INTEGER_TYPES = ("unsigned short", "unsigned long", "unsigned long long")
NONEXPLICIT_INTEGER_TYPES = (*SIGNED_NONEXPLICIT_INTEGER_TYPES, *UNSIGNED_NONEXPLICIT_INTEGER_TYPES)
FLOATING_POINT_TYPES = ("float", "double", "long double")
CHARACTER_TYPES = ("char", "wchar")
BOOLEAN_TYPE = "boolean"
OCTET_TYPE = "octet"
SIGNED_EXPLICIT_INTEGER_TYPES = ("int8", "int16", "int32", "int64")
UNSIGNED_EXPLICIT_INTEGER_TYPES = ("uint8", "uint16", "uint32", "uint64")
EXPLICIT_INTEGER_TYPES = (*SIGNED_EXPLICIT_INTEGER_TYPES, *UNSIGNED_EXPLICIT_INTEGER_TYPES)
SIGNED_INTEGER_TYPES = (*SIGNED_NONEXPLICIT_INTEGER_TYPES, *SIGNED_EXPLICIT_INTEGER_TYPES)
UNSIGNED_INTEGER_TYPES = (*UNSIGNED_NONEXPLICIT_INTEGER_TYPES, *UNSIGNED_EXPLICIT_INTEGER_TYPES)
INTEGER_TYPES = (*SIGNED_INTEGER_TYPES, *UNSIGNED_INTEGER_TYPES)
BASIC_TYPES = (*INTEGER_TYPES, *FLOATING_POINT_TYPES, *CHARACTER_TYPES, BOOLEAN_TYPE, OCTET_TYPE)

EMPTY_STRUCTURE_REQUIRED_MEMBER_NAME = "structure_needs_at_least_one_member"
CONSTANT_MODULE_SUFFIX = "_Constants"
SERVICE_REQUEST_MESSAGE_SUFFIX = "_Request"
SERVICE_RESPONSE_MESSAGE_SUFFIX = "_Response"
SERVICE_EVENT_MESSAGE_SUFFIX = "_Event"
ACTION_GOAL_SUFFIX = "_Goal"
ACTION_RESULT_SUFFIX = "_Result"
ACTION_FEEDBACK_SUFFIX = "_Feedback"
ACTION_GOAL_SERVICE_SUFFIX = "_SendGoal"
ACTION_RESULT_SERVICE_SUFFIX = "_GetResult"
ACTION_FEEDBACK_MESSAGE_SUFFIX = "_FeedbackMessage"


class AbstractType:
    __slots__ = ()

    def __eq__(self, other: object) -> bool:
        return type(self) is type(other)


class AbstractNestableType(AbstractType):
    """A type that may be the element of an array or sequence."""

    __slots__ = ()


class BasicType(AbstractNestableType):
    __slots__ = ("typename",)

    def __init__(self, typename: str) -> None:
        assert typename in BASIC_TYPES
        self.typename = typename

    def __eq__(self, other: object) -> bool:
        return super().__eq__(other) and self.typename == other.typename  # type: ignore[attr-defined]


class NamedType(AbstractNestableType):
    __slots__ = ("name",)

    def __init__(self, name: str) -> None:
        self.name = name

    def __eq__(self, other: object) -> bool:
        return super().__eq__(other) and self.name == other.name  # type: ignore[attr-defined]


class NamespacedType(AbstractNestableType):
    __slots__ = ("name", "namespaces")

    def __init__(self, namespaces: Iterable[str], name: str) -> None:
        self.namespaces = namespaces
        self.name = name

    def namespaced_name(self) -> tuple[str, ...]:
        return (*self.namespaces, self.name)

    def __eq__(self, other: object) -> bool:
        return (super().__eq__(other) and self.namespaces == other.namespaces  # type: ignore[attr-defined]
                and self.name == other.name)  # type: ignore[attr-defined]


class AbstractGenericString(AbstractNestableType):
    __slots__ = ()

    def has_maximum_size(self) -> bool:
        raise NotImplementedError("Only implemented in subclasses")


class AbstractString(AbstractGenericString):
    __slots__ = ()


class BoundedString(AbstractString):
    __slots__ = ("maximum_size",)

    def __init__(self, maximum_size: int) -> None:
        assert maximum_size >= 0
        self.maximum_size = maximum_size

    def has_maximum_size(self) -> bool:
        return True

    def __eq__(self, other: object) -> bool:
        return super().__eq__(other) and self.maximum_size == other.maximum_size  # type: ignore[attr-defined]


class UnboundedString(AbstractString):
    __slots__ = ()

    def has_maximum_size(self) -> bool:
        return False


class AbstractWString(AbstractGenericString):
    __slots__ = ()


class BoundedWString(AbstractWString):
    __slots__ = ("maximum_size",)

    def __init__(self, maximum_size: int) -> None:
        self.maximum_size = maximum_size

    def has_maximum_size(self) -> bool:
        return True

    def __eq__(self, other: object) -> bool:
        return super().__eq__(other) and self.maximum_size == other.maximum_size  # type: ignore[attr-defined]


class UnboundedWString(AbstractWString):
    __slots__ = ()

    def has_maximum_size(self) -> bool:
        return False


class AbstractNestedType(AbstractType):
    """Arrays and sequences: collections of a nestable type."""

    __slots__ = ("value_type",)

    def __init__(self, value_type: AbstractNestableType) -> None:
        assert isinstance(value_type, AbstractNestableType)
        self.value_type = value_type

    def has_maximum_size(self) -> bool:
        raise NotImplementedError("Only implemented in subclasses")

    def __eq__(self, other: object) -> bool:
        return super().__eq__(other) and self.value_type == other.value_type  # type: ignore[attr-defined]


class Array(AbstractNestedType):
    __slots__ = ("size",)

    def __init__(self, value_type: AbstractNestableType, size: int) -> None:
        super().__init__(value_type)
        assert size > 0
        self.size = size

    def has_maximum_size(self) -> bool:
        return True

    def __eq__(self, other: object) -> bool:
        return super().__eq__(other) and self.size == other.size  # type: ignore[attr-defined]


class AbstractSequence(AbstractNestedType):
    __slots__ = ()


class BoundedSequence(AbstractSequence):
    __slots__ = ("maximum_size",)

    def __init__(self, value_type: AbstractNestableType, maximum_size: int) -> None:
        super().__init__(value_type)
        assert maximum_size > 0
        self.maximum_size = maximum_size

    def has_maximum_size(self) -> bool:
        return True

    def __eq__(self, other: object) -> bool:
        return super().__eq__(other) and self.maximum_size == other.maximum_size  # type: ignore[attr-defined]


class UnboundedSequence(AbstractSequence):
    __slots__ = ()

    def has_maximum_size(self) -> bool:
        return False
