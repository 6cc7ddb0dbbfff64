"""`AnonName` (`$(anon name)`): a name made unique to this launch, the same for every use of `name`."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

from ..frontend.expose import expose_substitution
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_substitution('anon')
class AnonName(Substitution):
    """A unique name derived from `name`; it is remembered in the launch configurations as `'anon' + name`."""

    def __init__(self, name: SomeSubstitutionsType) -> None:
        super().__init__()
        self.__name = normalize_to_list_of_substitutions(name)

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        if len(data) != 1:
            raise TypeError('anon substitution expects 1 argument')
        return cls, {'name': data[0]}

    @property
    def name(self) -> list[Substitution]:
        return self.__name

    def describe(self) -> str:
        return 'AnonName({})'.format(' + '.join(sub.describe() for sub in self.name))

    def perform(self, context: LaunchContext) -> str:
        name = perform_substitutions(context, self.name)
        key = 'anon' + name
        if key not in context.launch_configurations:
            context.launch_configurations[key] = self.compute_name(name)
        return context.launch_configurations[key]

    def compute_name(self, id_value: str) -> str:
        """`id_value` with host, process id and a random number appended, as a valid ROS name."""
        import os
        import random
        import socket
        import sys

        name = f'{id_value}_{socket.gethostname()}_{os.getpid()}_{random.randint(0, sys.maxsize)}'
        for c in '.-:':
            name = name.replace(c, '_')
        return name
