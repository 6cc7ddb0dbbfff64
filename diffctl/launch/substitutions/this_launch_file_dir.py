"""`ThisLaunchFileDir`, `$(dirname)`: the folder of the launch file being loaded."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from .._private.operands import launch_file_local, tag_kwargs
from ..frontend.expose import expose_substitution
from ..substitution import Substitution

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_substitution('dirname')
class ThisLaunchFileDir(Substitution):
    """The folder holding the launch file whose include is being visited (fails outside one)."""

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        return cls, tag_kwargs(data, (), "dirname substitution doesn't expect arguments")

    def describe(self) -> str:
        return 'ThisLaunchFileDir()'

    def perform(self, context: LaunchContext) -> str:
        return launch_file_local(context, 'current_launch_file_directory', 'ThisLaunchFileDir')

    def __init__(self) -> None:
        super().__init__()
