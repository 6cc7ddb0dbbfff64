"""`FileContent`, `$(file-content path)`: the text of a file."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from .._private.operands import joined, tag_kwargs
from ..frontend.expose import expose_substitution
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions
from .substitution_failure import SubstitutionFailure

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_substitution('file-content')
class FileContent(Substitution):
    """Everything the file at `path` holds, read when performed; a missing file fails."""

    def __init__(self, path: SomeSubstitutionsType) -> None:
        super().__init__()
        self._where = normalize_to_list_of_substitutions(path)

    @property
    def path(self) -> list[Substitution]:
        return self._where

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        return cls, tag_kwargs(data, ('path',), 'file content substitutions expect 1 argument', error=AttributeError)

    def describe(self) -> str:
        return f"FileContent({joined(self._where, ', ')})"

    def perform(self, context: LaunchContext) -> str:
        where = perform_substitutions(context, self._where)
        try:
            with open(where) as stream:
                return stream.read()
        except FileNotFoundError:
            raise SubstitutionFailure(f'File not found: {where}') from None
