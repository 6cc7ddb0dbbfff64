"""`FindExecutable`, `$(find-exec name)`: an executable's path, looked up on PATH."""

from __future__ import annotations

import shutil
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


@expose_substitution('find-exec')
class FindExecutable(Substitution):
    """The first executable called `name` on PATH (as `shutil.which` finds it); none fails."""

    def __init__(self, *, name: SomeSubstitutionsType) -> None:
        super().__init__()
        self._program = normalize_to_list_of_substitutions(name)

    @property
    def name(self) -> list[Substitution]:
        return self._program

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        return cls, tag_kwargs(data, ('name',), 'find-exec substitution expects 1 argument', error=AttributeError)

    def describe(self) -> str:
        return f'FindExec({joined(self._program)})'

    def perform(self, context: LaunchContext) -> str:
        program = perform_substitutions(context, self._program)
        location = shutil.which(program)
        if location is None:
            raise SubstitutionFailure(f"executable '{program}' not found on the PATH")
        return location
