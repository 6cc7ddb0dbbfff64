"""`SomeSubstitutionsType`: what parameters taking "substitutions" accept — text, substitutions, or a mix."""

import collections.abc
from collections.abc import Iterable
from typing import Union

from .substitution import Substitution

SomeSubstitutionsType = Union[str, Substitution, Iterable[Union[str, Substitution]]]
SomeSubstitutionsType_types_tuple = (str, Substitution, collections.abc.Iterable)  # for isinstance checks
