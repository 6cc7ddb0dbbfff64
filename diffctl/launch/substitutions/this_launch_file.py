"""`ThisLaunchFile`, `$(filename)`: the launch file being loaded."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from .._private.operands import launch_file_local, tag_kwargs
from ..frontend.expose import expose_substitution
from ..substitution import Substitution

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_substitution('filename')
class ThisLaunchFile(Substitution):
    """The absolute path of the launch file whose include is being visited.

    Event handlers' actions and scripts have none: the substitution fails there.
    """

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        return cls, tag_kwargs(data, (), "filename substitution doesn't expect arguments")

    def describe(self) -> str:
        return 'ThisLaunchFile()'

    def perform(self, context: LaunchContext) -> str:
        return launch_file_local(context, 'current_launch_file_path', 'ThisLaunchFile')

    def __init__(self) -> None:
        super().__init__()
