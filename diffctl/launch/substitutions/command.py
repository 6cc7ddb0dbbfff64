"""`Command` (`$(command cmd [on_stderr])`): the standard output of a command."""

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

_ON_STDERR = ('fail', 'ignore', 'warn', 'capture')


@expose_substitution('command')
class Command(Substitution):
    """Runs `command` (split with shell rules, run without a shell) and stands for its standard output.

    A command that cannot start or exits non-zero is a SubstitutionFailure. `on_stderr` says what output on
    standard error does: 'fail' (a SubstitutionFailure), 'ignore', 'warn' (logged), or 'capture' (mixed
    into the result).
    """

    def __init__(self, command: SomeSubstitutionsType, *, on_stderr: SomeSubstitutionsType = 'fail') -> None:
        super().__init__()
        self.__command = normalize_to_list_of_substitutions(command)
        self.__on_stderr = normalize_to_list_of_substitutions(on_stderr)

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        if not 1 <= len(data) <= 2:
            raise ValueError('command substitution expects 1 or 2 arguments')
        kwargs = {'command': data[0]}
        if len(data) == 2:
            kwargs['on_stderr'] = data[1]
        return cls, kwargs

    @property
    def command(self) -> list[Substitution]:
        return self.__command

    @property
    def on_stderr(self) -> list[Substitution]:
        return self.__on_stderr

    def describe(self) -> str:
        return 'Command({})'.format(' + '.join(sub.describe() for sub in self.command))

    def perform(self, context: LaunchContext) -> str:
        import os
        import shlex
        import subprocess

        command_str = perform_substitutions(context, self.command)
        command = shlex.split(command_str) if os.name != 'nt' else command_str
        on_stderr = perform_substitutions(context, self.on_stderr)
        if on_stderr not in _ON_STDERR:
            raise SubstitutionFailure("expected 'on_stderr' to be one of: 'fail', 'ignore', 'warn' or 'capture'")
        try:
            result = subprocess.run(
                command,
                stdout=subprocess.PIPE,
                stderr=subprocess.STDOUT if on_stderr == 'capture' else subprocess.PIPE,
                text=True,
            )
        except FileNotFoundError as ex:
            raise SubstitutionFailure(f'file not found: {ex}') from ex
        if result.returncode != 0:
            message = f'executed command failed. Command: {command_str}'
            if result.stderr:
                message += f'\nCaptured stderr output: {result.stderr}'
            raise SubstitutionFailure(message)
        if result.stderr:
            message = (
                f'executed command showed stderr output. Command: {command_str}\n'
                f'Captured stderr output:\n{result.stderr}')
            if on_stderr == 'fail':
                raise SubstitutionFailure(message)
            if on_stderr == 'warn':
                from .. import logging as launch_logging

                launch_logging.get_logger().warning(message)
        return result.stdout
