"""`LaunchLogDir`, `$(launch_log_dir)` or `$(log_dir)`: where this launch writes its logs."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from .._private.operands import tag_kwargs
from ..frontend.expose import expose_substitution
from ..substitution import Substitution

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_substitution('launch_log_dir')
@expose_substitution('log_dir')
class LaunchLogDir(Substitution):
    """The log folder of the running launch (`launch.logging.launch_config.log_dir`), made on first use."""

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        return cls, tag_kwargs(data, (), "launch_log_dir/log_dir substitution doesn't expect arguments")

    def describe(self) -> str:
        return 'LaunchLogDir()'

    def perform(self, context: LaunchContext) -> str:
        from .. import logging as launch_logging

        return launch_logging.launch_config.log_dir

    def __init__(self) -> None:
        super().__init__()
