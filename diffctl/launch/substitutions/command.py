"""`Command`, `$(command cmd [on_stderr])`: what a command prints."""

from __future__ import annotations

import os
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

# what output on standard error does to the substitution
_STDERR_POLICIES = ('fail', 'ignore', 'warn', 'capture')


def _run(line: str, merge_stderr: bool):
    import shlex
    import subprocess

    argv = line if os.name == 'nt' else shlex.split(line)
    try:
        return subprocess.run(
            argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT if merge_stderr else subprocess.PIPE,
            text=True)
    except FileNotFoundError as missing:
        raise SubstitutionFailure(f'file not found: {missing}') from missing


@expose_substitution('command')
class Command(Substitution):
    """The standard output of `command`, split into words by shell rules and run without a shell.

    It fails when the command cannot be started or exits non-zero. Text on standard error, per
    `on_stderr`: 'fail' fails the substitution, 'ignore' drops it, 'warn' logs it, 'capture' keeps it
    in the result, interleaved with standard output.
    """

    def __init__(self, command: SomeSubstitutionsType, *, on_stderr: SomeSubstitutionsType = 'fail') -> None:
        super().__init__()
        self._line = normalize_to_list_of_substitutions(command)
        self._stderr_policy = normalize_to_list_of_substitutions(on_stderr)

    @property
    def command(self) -> list[Substitution]:
        return self._line

    @property
    def on_stderr(self) -> list[Substitution]:
        return self._stderr_policy

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        kwargs = tag_kwargs(
            data, ('command', 'on_stderr'), 'command substitution expects 1 or 2 arguments', required=1,
            error=ValueError)
        return cls, kwargs

    def describe(self) -> str:
        return f'Command({joined(self._line)})'

    def perform(self, context: LaunchContext) -> str:
        line = perform_substitutions(context, self._line)
        policy = perform_substitutions(context, self._stderr_policy)
        if policy not in _STDERR_POLICIES:
            raise SubstitutionFailure("expected 'on_stderr' to be one of: 'fail', 'ignore', 'warn' or 'capture'")
        finished = _run(line, merge_stderr=policy == 'capture')
        if finished.returncode != 0:
            complaint = f'executed command failed. Command: {line}'
            if finished.stderr:
                complaint = f'{complaint}\nCaptured stderr output: {finished.stderr}'
            raise SubstitutionFailure(complaint)
        if finished.stderr and policy in ('fail', 'warn'):
            complaint = (
                f'executed command showed stderr output. Command: {line}\nCaptured stderr output:\n{finished.stderr}')
            if policy == 'fail':
                raise SubstitutionFailure(complaint)
            from .. import logging as launch_logging

            launch_logging.get_logger().warning(complaint)
        return finished.stdout
