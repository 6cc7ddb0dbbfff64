"""`FileContent` (`$(file-content path)`): the text of a file."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

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
    """The content of the file at `path`; a missing file is a SubstitutionFailure."""

    def __init__(self, path: SomeSubstitutionsType) -> None:
        super().__init__()
        self.__path = normalize_to_list_of_substitutions(path)

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        if not data or len(data) != 1:
            raise AttributeError('file content substitutions expect 1 argument')
        return cls, {'path': data[0]}

    @property
    def path(self) -> list[Substitution]:
        return self.__path

    def describe(self) -> str:
        return 'FileContent({})'.format(', '.join(sub.describe() for sub in self.path))

    def perform(self, context: LaunchContext) -> str:
        path = perform_substitutions(context, self.path)
        try:
            with open(path) as f:
                return f.read()
        except FileNotFoundError:
            raise SubstitutionFailure(f'File not found: {path}') from None
