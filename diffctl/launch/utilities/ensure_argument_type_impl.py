"""`ensure_argument_type`: a TypeError naming the argument when a value has the wrong type."""

from __future__ import annotations

import collections.abc
import inspect
from collections.abc import Iterable
from typing import Any

_MESSAGE = "{}xpected '{}' to be one of [{}], but got '{}' of type '{}'"


def _misuse(name: str, wanted: str, value: Any) -> TypeError:
    return TypeError(_MESSAGE.format("'ensure_argument_type()' e", name, wanted, value, type(value)))


def _matches(argument: Any, candidate: Any) -> bool:
    if isinstance(argument, candidate):
        return True
    return inspect.isclass(candidate) and issubclass(type(argument), candidate)


def ensure_argument_type(
    argument: Any,
    types: type | Iterable[type],
    argument_name: str,
    caller: str | None = None,
) -> None:
    """Raise TypeError unless `argument` is an instance of one of `types` (a type or an iterable of them).

    The message names `argument_name` and, when given, the `caller`.
    """
    # the common case first, without building anything: a launch makes many actions, each checking several
    if type(argument_name) is str and (caller is None or type(caller) is str):
        if isinstance(types, type):
            if isinstance(argument, types):
                return
        elif type(types) in (list, tuple) and all(isinstance(t, type) for t in types) \
                and isinstance(argument, tuple(types)):
            return
    if not isinstance(types, (type, collections.abc.Iterable)):
        raise _misuse('types', 'type, collections.abc.Iterable of type', types)
    if not isinstance(argument_name, str):
        raise _misuse('argument_name', 'str', argument_name)
    if caller is not None and not isinstance(caller, str):
        raise _misuse('caller', 'str, None', caller)
    candidates = list(types) if isinstance(types, collections.abc.Iterable) else [types]
    if any(_matches(argument, candidate) for candidate in candidates):
        return
    who = 'E' if caller is None else f"'{caller}' e"
    raise TypeError(_MESSAGE.format(
        who, argument_name, ', '.join(str(t) for t in candidates), argument, type(argument)))
