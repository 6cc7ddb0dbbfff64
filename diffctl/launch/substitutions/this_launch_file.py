"""`ThisLaunchFile` (`$(filename)`): the path of the launch file being run."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from ..frontend.expose import expose_substitution
from ..substitution import Substitution
from .substitution_failure import SubstitutionFailure

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_substitution('filename')
class ThisLaunchFile(Substitution):
    """The absolute path of the current launch file; outside one (a script) it is a SubstitutionFailure."""

    def __init__(self) -> None:
        super().__init__()

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        if len(data) != 0:
            raise TypeError("filename substitution doesn't expect arguments")
        return cls, {}

    def describe(self) -> str:
        return 'ThisLaunchFile()'

    def perform(self, context: LaunchContext) -> str:
        if 'current_launch_file_path' not in context.get_locals_as_dict():
            raise SubstitutionFailure('ThisLaunchFile used outside of a launch file (in a script)')
        return context.locals.current_launch_file_path
