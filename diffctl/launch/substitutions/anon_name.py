"""`AnonName`, `$(anon name)`: a name no other launch uses, stable within this one."""

from __future__ import annotations

import os
import re
import sys
from collections.abc import Sequence
from typing import TYPE_CHECKING

from .._private.operands import joined, tag_kwargs
from ..frontend.expose import expose_substitution
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType

_NOT_IN_ROS_NAMES = re.compile('[.:-]')


@expose_substitution('anon')
class AnonName(Substitution):
    """`name` made unique; every `AnonName` of the same name in a launch gives the same text.

    The text is kept as the launch configuration `'anon' + name`, which is how later uses find it.
    """

    def __init__(self, name: SomeSubstitutionsType) -> None:
        super().__init__()
        self._base = normalize_to_list_of_substitutions(name)

    @property
    def name(self) -> list[Substitution]:
        return self._base

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        return cls, tag_kwargs(data, ('name',), 'anon substitution expects 1 argument')

    def describe(self) -> str:
        return f'AnonName({joined(self._base)})'

    def perform(self, context: LaunchContext) -> str:
        base = perform_substitutions(context, self._base)
        remembered = context.launch_configurations
        key = f'anon{base}'
        if key not in remembered:
            remembered[key] = self.compute_name(base)
        return remembered[key]

    def compute_name(self, id_value: str) -> str:
        """`id_value`, this host, this process and a random number, as one valid ROS name."""
        import random  # not at import time: loading launch stays cheap
        import socket

        unique = f'{id_value}_{socket.gethostname()}_{os.getpid()}_{random.randint(0, sys.maxsize)}'
        return _NOT_IN_ROS_NAMES.sub('_', unique)
