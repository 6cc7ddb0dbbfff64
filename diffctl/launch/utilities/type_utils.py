"""Typed values that may hold substitutions: checking, coercing from text, normalizing and performing.

The allowed types are the scalars `int`, `float`, `bool`, `str` and uniform lists of one of them
(`List[int]`, …). Text is coerced with YAML's rules (`'1.5'` → 1.5, `'true'` → True, `'[1, 2]'` → [1, 2]),
except that `'1'`/`'0'` are also true/false where a `bool` is wanted. A "normalized" typed value is either
a plain value or a list of substitutions (`List[Substitution]`), or for lists a list whose items are
plain values or lists of substitutions; `perform_typed_substitution` turns it into the final value.
"""

from __future__ import annotations

import collections.abc
from typing import TYPE_CHECKING, Any, List, Sequence, Type, Union

from ..some_substitutions_type import SomeSubstitutionsType
from ..substitution import Substitution
from .ensure_argument_type_impl import ensure_argument_type
from .normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from .perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from ..launch_context import LaunchContext

__all__ = [
    'AllowedTypesTuple', 'AllowedTypesType', 'AllowedValueType', 'ListTypesTuple', 'ListTypesType',
    'ListValueType', 'NormalizedScalarType', 'NormalizedSequenceType', 'NormalizedValueType',
    'ScalarTypesTuple', 'ScalarTypesType', 'ScalarValueType', 'SequenceValueType', 'SomeScalarType',
    'SomeSequenceType', 'SomeValueType', 'StrSomeScalarType', 'StrSomeSequenceType', 'StrSomeValueType',
    'coerce_list', 'coerce_to_type', 'extract_type', 'get_typed_value', 'is_instance_of',
    'is_instance_of_valid_type', 'is_normalized_substitution', 'is_substitution', 'is_typing_list',
    'is_valid_scalar_type', 'normalize_typed_substitution', 'perform_substitutions',
    'perform_typed_substitution',
]

# ros2/launch's public aliases, built from the four scalar types. `Union[tuple]` is `Union[a, b, …]`; the
# typing objects compare equal to those written out, which is what users' annotations and checks see.
ScalarTypesTuple = (int, float, bool, str)
ListTypesTuple = tuple(List[scalar] for scalar in ScalarTypesTuple)
AllowedTypesTuple = ScalarTypesTuple + ListTypesTuple

ScalarValueType = Union[ScalarTypesTuple]
ListValueType = Union[ListTypesTuple]
SequenceValueType = Union[tuple(Sequence[scalar] for scalar in ScalarTypesTuple)]
AllowedValueType = Union[ScalarValueType, SequenceValueType]

ScalarTypesType = Type[ScalarValueType]
ListTypesType = Type[ListValueType]
AllowedTypesType = Union[ScalarTypesType, ListTypesType]

# before substitution (Some…), after normalization (Normalized…), and as read from markup (StrSome…)
SomeScalarType = Union[SomeSubstitutionsType, ScalarValueType]
SomeSequenceType = Union[tuple(Sequence[Union[scalar, SomeSubstitutionsType]] for scalar in ScalarTypesTuple)]
SomeValueType = Union[SomeScalarType, SomeSequenceType]
NormalizedScalarType = Union[List[Substitution], ScalarValueType]
NormalizedSequenceType = Union[tuple(List[Union[scalar, List[Substitution]]] for scalar in ScalarTypesTuple)]
NormalizedValueType = Union[NormalizedScalarType, NormalizedSequenceType]
StrSomeScalarType = SomeScalarType
StrSomeSequenceType = Union[tuple(Sequence[Union[scalar, str]] for scalar in ScalarTypesTuple)]
StrSomeValueType = Union[StrSomeScalarType, StrSomeSequenceType]


# ---- type objects -------------------------------------------------------------------------------------------

def is_typing_list(data_type: Any) -> bool:
    """True for `typing.List`, `List[X]` and `list[X]`."""
    if data_type is List:
        return True
    return getattr(data_type, '__origin__', None) is list and hasattr(data_type, '__args__')


def is_valid_scalar_type(data_type: AllowedTypesType) -> bool:
    """True for `int`, `float`, `bool` and `str`."""
    return data_type in ScalarTypesTuple


def extract_type(data_type: AllowedTypesType) -> tuple[ScalarTypesType, bool]:
    """(scalar type, is a list) of an allowed type: `List[int]` → (int, True), `bool` → (bool, False).

    ValueError for anything else.
    """
    scalar, is_list = data_type, False
    args = getattr(data_type, '__args__', None)
    if is_typing_list(data_type) and args:
        scalar, is_list = args[0], True
    if not is_valid_scalar_type(scalar):
        raise ValueError(f'Unrecognized data type: {data_type}')
    return scalar, is_list


# ---- checking values ----------------------------------------------------------------------------------------

def is_instance_of_valid_type(value: Any, *, can_be_str: bool = False) -> bool:
    """True when `value` is an allowed scalar or a uniform list of one (empty lists included).

    With `can_be_str`, a list may mix strings into items of its one other scalar type.
    """
    if not isinstance(value, list):
        return isinstance(value, ScalarTypesTuple)
    if not value:
        return True
    item_type = next((type(x) for x in value if type(x) is not str), str)
    if item_type not in ScalarTypesTuple:
        return False
    accepted = (item_type, str) if can_be_str else item_type
    return all(isinstance(x, accepted) for x in value)


def is_instance_of(value: Any, data_type: AllowedTypesType | None = None, *, can_be_str: bool = False) -> bool:
    """True when `value` is of `data_type` (any allowed type when None); `can_be_str` also accepts strings."""
    if data_type is None:
        return is_instance_of_valid_type(value, can_be_str=can_be_str)
    scalar, is_list = extract_type(data_type)
    accepted: Any = (str, scalar) if can_be_str else scalar
    if not is_list:
        return isinstance(value, accepted)
    return isinstance(value, list) and all(isinstance(x, accepted) for x in value)


# ---- coercing text ------------------------------------------------------------------------------------------

def _from_yaml(text: str, failure: str, can_be_str: bool) -> Any:
    if not text:
        return text
    import yaml

    try:
        value = yaml.safe_load(text)
    except Exception as err:
        if can_be_str:
            return text
        raise ValueError(f'{failure}: yaml.safe_load() failed\n{err}') from err
    if not is_instance_of_valid_type(value, can_be_str=can_be_str):
        raise ValueError(f'{failure}: output type is not allowed, got {type(value)}')
    return value


def coerce_to_type(
    value: str, data_type: AllowedTypesType | None = None, *, can_be_str: bool = False
) -> StrSomeValueType:
    """`value` (a string) converted to `data_type`; None picks the type YAML reads.

    With `can_be_str`, text that does not convert is returned unchanged (and lists may hold strings):
    the frontends use it for attributes that may embed substitutions. ValueError when the conversion
    fails or `data_type` is not allowed, TypeError when `value` is not a string.
    """
    ensure_argument_type(value, str, 'value', 'coerce_to_type')
    if data_type is None:
        return _from_yaml(value, f"Failed to convert '{value}' using yaml rules", can_be_str)
    scalar, is_list = extract_type(data_type)
    accepted: Any = (str, scalar) if can_be_str else scalar
    if is_list:
        failure = f"Cannot convert value '{value}' to a list of '{accepted}'"
        items = _from_yaml(value, failure, can_be_str)
        if not isinstance(items, list):
            raise ValueError(failure)
        if not all(isinstance(x, accepted) for x in items):
            raise ValueError(f'{failure}, got {items}')
        return items
    if scalar is str:
        return value
    if scalar in (int, float):
        try:
            return scalar(value)
        except ValueError:
            if can_be_str:
                return value
            raise
    # bool: '1' and '0' count as true and false as well as YAML's spellings
    text = {'1': 'true', '0': 'false'}.get(value, value)
    result = _from_yaml(text, f"Failed to convert '{text}' to '{scalar}'", can_be_str)
    if isinstance(result, accepted):
        return result
    raise ValueError(f"Cannot convert value '{text}' to '{scalar}'")


def coerce_list(
    value: list[str], data_type: ScalarTypesType | None = None, *, can_be_str: bool = False
) -> StrSomeSequenceType:
    """Each string of `value` coerced to the scalar `data_type`; the result must be a uniform list."""
    ensure_argument_type(value, list, 'value', 'coerce_list')
    result = [coerce_to_type(item, data_type, can_be_str=can_be_str) for item in value]
    if not is_instance_of_valid_type(result, can_be_str=can_be_str):
        raise ValueError(f'cannot convert value to {data_type}. Got value=`{value}`')
    return result


def get_typed_value(
    value: str | list[str], data_type: AllowedTypesType | None, *, can_be_str: bool = False
) -> StrSomeValueType:
    """A string coerced to `data_type`, or a list of strings coerced item by item to a list type.

    TypeError when a list is given for a scalar type.
    """
    if not isinstance(value, list):
        return coerce_to_type(value, data_type, can_be_str=can_be_str)
    scalar = None
    if data_type is not None:
        scalar, is_list = extract_type(data_type)
        if not is_list:
            raise TypeError(f"Cannot convert input '{value}' of type '{type(value)}' to '{scalar}'")
    return coerce_list(value, scalar, can_be_str=can_be_str)


# ---- values holding substitutions ---------------------------------------------------------------------------

def is_substitution(x: Any) -> bool:
    """True for a Substitution, or a non-empty iterable of strings and substitutions holding at least one."""
    if isinstance(x, Substitution):
        return True
    if isinstance(x, str) or not isinstance(x, collections.abc.Iterable):
        return False
    return (
        len(x) > 0
        and all(isinstance(i, (Substitution, str)) for i in x)
        and any(isinstance(i, Substitution) for i in x)
    )


def is_normalized_substitution(x: Any) -> bool:
    """True for a non-empty list made only of substitutions."""
    return isinstance(x, list) and bool(x) and all(isinstance(i, Substitution) for i in x)


def _item_kind(item: Any, value: Any) -> type:
    if isinstance(item, ScalarTypesTuple):
        return type(item)
    if is_substitution(item):
        return Substitution
    raise TypeError(
        'value is a list, and one of the items is not a scalar, a Substitution '
        f"or a list of substitutions. Got value='{value}'")


def normalize_typed_substitution(value: SomeValueType, data_type: AllowedTypesType | None) -> NormalizedValueType:
    """Normalize a value that is of `data_type` or will become it once its substitutions are performed.

    A scalar is checked and returned; a substitution (or a mix of strings and substitutions) becomes one
    list of substitutions; a list of items becomes a list of plain items and lists of substitutions, whose
    plain items must agree with `data_type` (a list of strings and substitutions counts as ONE substitution:
    write `['a', [TextSubstitution(text='b')]]` for two items). TypeError when the value cannot become a
    `data_type`, ValueError when `data_type` is not allowed.
    """
    if is_substitution(value):
        return normalize_to_list_of_substitutions(value)
    if isinstance(value, ScalarTypesTuple):
        if is_instance_of(value, data_type):
            return value
        raise TypeError(f"value='{value}' is not an instance of {data_type}")
    if not isinstance(value, collections.abc.Iterable):
        raise TypeError(
            'value should be either a scalar, a substitutions, or a mixed list of scalars and substitutions. '
            f'Got `value={value}` of type `{type(value)}`. ')
    items = list(value)
    kinds = {_item_kind(item, value) for item in items}
    scalar: Any = None
    if data_type is not None:
        scalar, is_list = extract_type(data_type)
        if not is_list:
            raise TypeError(
                'The provided value resolves to a list, though the required type is a scalar. '
                f"Got value='{value}', data_type='{scalar}'.")

    def wrong(kind: type) -> TypeError:
        return TypeError(f"Got a list of '{kind}', expected a list of '{scalar}'. value='{value}'")

    def subs(item: Any) -> Any:
        return normalize_to_list_of_substitutions(item) if is_substitution(item) else item

    if kinds <= {Substitution}:
        return [normalize_to_list_of_substitutions(item) for item in items]
    for kind, allowed in ((str, {str, Substitution}), (bool, {bool, Substitution}), (int, {int, Substitution})):
        if kinds <= allowed:
            if scalar not in (None, kind):
                raise wrong(kind)
            return [subs(item) for item in items]
    if kinds <= {int, float, Substitution}:
        if scalar not in (None, float):
            raise wrong(float)
        return [subs(item) if is_substitution(item) else float(item) for item in items]
    raise TypeError(f"Input value is not an acceptable 'SomeValueType'.Got value='{value}'")


def perform_typed_substitution(
    context: LaunchContext, value: NormalizedValueType, data_type: AllowedTypesType | None
) -> StrSomeValueType:
    """Perform the substitutions of a normalized typed value and coerce the result to `data_type`.

    TypeError when a scalar is not of `data_type` or the value is not normalized; ValueError when the
    performed text does not convert, or a list is given for a scalar type.
    """
    if isinstance(value, ScalarTypesTuple):
        if data_type is not None and not is_instance_of(value, data_type):
            raise TypeError(f'value=`{value}` is a scalar and not an instance of `{data_type}`')
        return value
    if is_normalized_substitution(value):
        return coerce_to_type(perform_substitutions(context, value), data_type)
    if isinstance(value, list):
        scalar = None
        if data_type is not None:
            scalar, is_list = extract_type(data_type)
            if not is_list:
                raise ValueError(
                    'The input value is a list, cannot convert it to a scalar. '
                    f"Got value='{value}', expected type {scalar}.")
        result = [
            coerce_to_type(perform_substitutions(context, item), scalar)
            if is_normalized_substitution(item) else item
            for item in value
        ]
        if not is_instance_of(result, data_type):
            if scalar is not None:
                raise ValueError(
                    'The output list does not match the expected type '
                    f"Got value='{value}', expected type {scalar}.")
            raise ValueError('The output list is not uniform')
        return result
    raise TypeError(f"Input value is not an acceptable 'NormalizedValueType'.Got value='{value}'")
