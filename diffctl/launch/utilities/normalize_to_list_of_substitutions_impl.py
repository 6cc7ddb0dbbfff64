"""`normalize_to_list_of_substitutions`: strings and substitutions into a list of substitutions."""

from __future__ import annotations

from ..some_substitutions_type import SomeSubstitutionsType
from ..substitution import Substitution
from .class_tools_impl import is_a_subclass


def normalize_to_list_of_substitutions(subs: SomeSubstitutionsType) -> list[Substitution]:
    """A list of substitutions from a string, a substitution, or an iterable of strings and substitutions.

    Strings become `TextSubstitution`s; anything else raises TypeError.
    """
    from ..substitutions.text_substitution import TextSubstitution

    if isinstance(subs, str):
        return [TextSubstitution(text=subs)]
    if is_a_subclass(subs, Substitution):
        return [subs]
    result: list[Substitution] = []
    for item in subs:
        if isinstance(item, Substitution):
            result.append(item)
        elif isinstance(item, str):
            result.append(TextSubstitution(text=item))
        else:
            raise TypeError(
                f"Failed to normalize given item of type '{type(item)}', when only "
                "'str' or 'launch.Substitution' were expected.")
    return result
